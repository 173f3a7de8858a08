// Velocity constraints and face loads (see header and docs/mpm.md, "Tractions").
#include "mpm/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "common/errors.hpp"

namespace mpm {

VelocityConstraint face_constraint(const Grid& grid, int axis, int side, std::array<bool, 3> fixed,
                                   const common::Vec3& velocity) {
  if (axis < 0 || axis > 2 || (side != -1 && side != 1)) {
    throw common::InputError("mpm face constraint: axis = " + std::to_string(axis) + ", side = " +
                             std::to_string(side) + ": axis must be 0..2 and side -1 or +1");
  }
  VelocityConstraint c;
  c.lo = grid.origin;
  c.hi = grid.upper();
  const double plane = side < 0 ? grid.origin[axis] : grid.upper()[axis];
  c.lo[axis] = plane;
  c.hi[axis] = plane;
  c.fixed = fixed;
  c.velocity = velocity;
  return c;
}

ResolvedConstraint resolve(const Grid& grid, const VelocityConstraint& c) {
  ResolvedConstraint r{c, {}};
  const common::Vec3 tol = 1e-9 * grid.spacing;
  for (std::int64_t i = 0; i < grid.num_nodes(); ++i) {
    const common::Vec3 x = grid.node_position(i);
    if (((x - c.lo + tol).array() >= 0.0).all() && ((c.hi + tol - x).array() >= 0.0).all()) {
      r.nodes.push_back(i);
    }
  }
  return r;
}

namespace {
common::Vec3 prescribed(const Grid& grid, const VelocityConstraint& c, std::int64_t node, double t) {
  return c.field ? c.field(grid.node_position(node), t) : c.velocity;
}
}  // namespace

void apply_velocity_constraints(const Grid& grid, const std::vector<ResolvedConstraint>& cs,
                                double t, GridFields& fields) {
  for (const ResolvedConstraint& c : cs) {
    for (const std::int64_t i : c.nodes) {
      const auto u = static_cast<std::size_t>(i);
      if (!fields.is_active[u]) continue;
      const common::Vec3 v = prescribed(grid, c.spec, i, t);
      for (int d = 0; d < 3; ++d) {
        if (c.spec.fixed[static_cast<std::size_t>(d)]) fields.velocity[u][d] = v[d];
      }
    }
  }
}

void apply_acceleration_constraints(const Grid& grid, const std::vector<ResolvedConstraint>& cs,
                                    double t, double dt, GridFields& fields) {
  for (const ResolvedConstraint& c : cs) {
    for (const std::int64_t i : c.nodes) {
      const auto u = static_cast<std::size_t>(i);
      if (!fields.is_active[u]) continue;
      common::Vec3 a = common::Vec3::Zero();
      if (c.spec.field) a = (c.spec.field(grid.node_position(i), t + dt) - c.spec.field(grid.node_position(i), t)) / dt;
      for (int d = 0; d < 3; ++d) {
        if (c.spec.fixed[static_cast<std::size_t>(d)]) fields.acceleration[u][d] = a[d];
      }
    }
  }
}

MaterialExtent material_extent(const MaterialPoints& points) {
  MaterialExtent e{common::Vec3::Constant(INFINITY), common::Vec3::Constant(-INFINITY)};
  for (std::size_t p = 0; p < points.size(); ++p) {
    const common::Vec3 half = points.F[p].cwiseAbs() * points.half_width0[p];
    e.lo = e.lo.cwiseMin(points.x[p] - half);
    e.hi = e.hi.cwiseMax(points.x[p] + half);
  }
  return e;
}

namespace {

/// Range of s (cell units) where the stencil of `kind` lies inside the grid along one axis.
void valid_range(ShapeKind kind, int cells, double& s_lo, double& s_hi) {
  const double margin = kind == ShapeKind::bspline2 ? 0.5 : 0.0;
  s_lo = margin;
  s_hi = std::nextafter(cells - margin, 0.0);
}

/// Basis used for face loads: the grid functions (uGIMP's grid basis is the linear hat).
ShapeKind face_basis(ShapeKind kind) {
  return kind == ShapeKind::bspline2 ? ShapeKind::bspline2 : ShapeKind::linear;
}

/// Integrals over [a, b] (cell units) of the basis functions of each node, exact for the
/// piecewise-quadratic bases: split at every half cell, 2-point Gauss on each piece.
std::map<int, double> basis_integrals(ShapeKind kind, double a, double b, double h) {
  std::map<int, double> out;
  if (!(b > a)) return out;
  const double g = 0.5 / std::sqrt(3.0);
  double lo = a;
  while (lo < b) {
    const double hi = std::min(b, (std::floor(lo * 2.0) + 1.0) / 2.0);
    const double mid = 0.5 * (lo + hi);
    const double len = hi - lo;
    for (const double xi : {mid - g * len, mid + g * len}) {
      const Weights1D w = weights_1d(kind, xi, 0.0, h);
      for (int k = 0; k < stencil_width(kind); ++k) {
        out[w.base + k] += 0.5 * len * h * w.w[static_cast<std::size_t>(k)];
      }
    }
    lo = hi;
  }
  return out;
}

}  // namespace

double apply_traction(const Grid& grid, ShapeKind kind, const TractionLoad& load,
                      const MaterialExtent& extent, GridFields& fields) {
  const int n = load.axis;
  if (n < 0 || n > 2 || (load.side != -1 && load.side != 1)) {
    throw common::InputError("mpm traction load: axis = " + std::to_string(n) + ", side = " +
                             std::to_string(load.side) + ": axis must be 0..2 and side -1 or +1");
  }
  const int t1 = (n + 1) % 3;
  const int t2 = (n + 2) % 3;
  const double area = (extent.hi[t1] - extent.lo[t1]) * (extent.hi[t2] - extent.lo[t2]);
  common::Vec3 normal = common::Vec3::Zero();
  normal[n] = load.side;
  const common::Vec3 total = (load.traction - load.pressure * normal) * area;

  const ShapeKind basis = face_basis(kind);
  std::array<std::map<int, double>, 3> integral;
  for (const int d : {t1, t2}) {
    double s_lo = 0.0;
    double s_hi = 0.0;
    valid_range(basis, grid.cells[d], s_lo, s_hi);
    const double a = std::clamp((extent.lo[d] - grid.origin[d]) / grid.spacing[d], s_lo, s_hi);
    const double b = std::clamp((extent.hi[d] - grid.origin[d]) / grid.spacing[d], s_lo, s_hi);
    integral[static_cast<std::size_t>(d)] = basis_integrals(basis, a, b, grid.spacing[d]);
  }
  double s_lo = 0.0;
  double s_hi = 0.0;
  valid_range(basis, grid.cells[n], s_lo, s_hi);
  const double face = load.side < 0 ? extent.lo[n] : extent.hi[n];
  const double s_face = std::clamp((face - grid.origin[n]) / grid.spacing[n], s_lo, s_hi);
  const Weights1D wn = weights_1d(basis, s_face, 0.0, grid.spacing[n]);

  // Weights of the active nodes, in node order, then scaled to carry exactly total.
  std::map<std::int64_t, double> weight;
  double sum = 0.0;
  for (int k = 0; k < stencil_width(basis); ++k) {
    const double w_n = wn.w[static_cast<std::size_t>(k)];
    if (w_n == 0.0) continue;
    for (const auto& [i1, I1] : integral[static_cast<std::size_t>(t1)]) {
      for (const auto& [i2, I2] : integral[static_cast<std::size_t>(t2)]) {
        common::Vec3i ijk;
        ijk[n] = wn.base + k;
        ijk[t1] = i1;
        ijk[t2] = i2;
        const std::int64_t node = grid.node_index(ijk[0], ijk[1], ijk[2]);
        const double w = w_n * I1 * I2;
        if (w == 0.0 || !fields.is_active[static_cast<std::size_t>(node)]) continue;
        weight[node] += w;
        sum += w;
      }
    }
  }
  if (!(sum > 0.0)) {
    throw common::NumericalError("mpm traction load on axis " + std::to_string(n) + " side " +
                                 std::to_string(load.side) +
                                 ": the loaded face touches no node holding material");
  }
  for (const auto& [node, w] : weight) fields.force[static_cast<std::size_t>(node)] += (w / sum) * total;
  return area;
}

}  // namespace mpm
