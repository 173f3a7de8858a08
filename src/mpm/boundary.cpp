// Velocity constraints and face loads (see header and docs/design/mpm.md, "Tractions").
#include "mpm/boundary.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>

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

VelocityConstraint node_constraint(const Grid& grid, const common::Vec3& node,
                                   std::array<bool, 3> fixed, const common::Vec3& velocity) {
  VelocityConstraint c;
  // A box of a quarter spacing around the node selects it and no neighbour.
  c.lo = node - 0.25 * grid.spacing;
  c.hi = node + 0.25 * grid.spacing;
  c.fixed = fixed;
  c.velocity = velocity;
  return c;
}

ResolvedConstraint resolve(const Grid& grid, const VelocityConstraint& c) {
  ResolvedConstraint r{c, {}, {}};
  const common::Vec3 tol = 1e-9 * grid.spacing;
  const int m = c.mirror_axis;
  if (m > 2)
    throw common::InputError("mpm constraint: mirror_axis = " + std::to_string(m) +
                             ": must be -1 or 0..2");
  if (c.has_wall()) {
    if (c.wall.axis > 2 || (c.wall.side != -1 && c.wall.side != 1) || !(c.wall.mu >= 0.0)) {
      throw common::InputError("mpm constraint: wall axis = " + std::to_string(c.wall.axis) +
                               ", side = " + std::to_string(c.wall.side) +
                               ", friction = " + std::to_string(c.wall.mu) +
                               ": axis must be 0..2, side -1 or +1 and friction >= 0");
    }
    if (m >= 0) throw common::InputError("mpm constraint: a wall cannot have a mirror");
  }
  if (!(c.from < c.until)) {
    throw common::InputError("mpm constraint: from = " + std::to_string(c.from) + " s, until = " +
                             std::to_string(c.until) + " s: from must be before until");
  }
  double plane_index = 0.0;
  if (m >= 0) {
    plane_index = (c.mirror_plane - grid.origin[m]) / grid.spacing[m];
    if (std::abs(plane_index - std::round(plane_index)) > 1e-9) {
      throw common::InputError("mpm constraint: mirror_plane = " + std::to_string(c.mirror_plane) +
                               ": must be a node plane of the grid along axis " +
                               std::to_string(m));
    }
    plane_index = std::round(plane_index);
  }
  for (std::int64_t i = 0; i < grid.num_nodes(); ++i) {
    const common::Vec3 x = grid.node_position(i);
    if (((x - c.lo + tol).array() >= 0.0).all() && ((c.hi + tol - x).array() >= 0.0).all()) {
      if (m < 0) {
        r.nodes.push_back(i);
        continue;
      }
      common::Vec3i ijk = grid.node_ijk(i);
      const int k = static_cast<int>(plane_index);
      const int mirrored = 2 * k - ijk[m];
      if (ijk[m] == k) {
        r.nodes.push_back(i);
        r.mirror.push_back(-1);
      } else if (mirrored >= 0 && mirrored <= grid.cells[m]) {
        ijk[m] = mirrored;
        r.nodes.push_back(i);
        r.mirror.push_back(grid.node_index(ijk[0], ijk[1], ijk[2]));
      }
    }
  }
  return r;
}

namespace {
common::Vec3 prescribed(const Grid& grid, const VelocityConstraint& c, std::int64_t node,
                        double t) {
  return c.field ? c.field(grid.node_position(node), t) : c.velocity;
}

/// Whether a node may be touched this step (it holds mass, or it is in a stencil).
bool node_active(const GridFields& fields, std::size_t u) { return fields.is_active[u] != 0; }
}  // namespace

common::Vec3 prescribed_velocity(const VelocityConstraint& c, double t) {
  common::Vec3 v = c.field ? c.field(0.5 * (c.lo + c.hi), t) : c.velocity;
  if (!c.has_wall()) {
    for (int d = 0; d < 3; ++d) {
      if (!c.fixed[static_cast<std::size_t>(d)]) v[d] = 0.0;
    }
  }
  return v;
}

void apply_velocity_constraints(const Grid& grid, const std::vector<ResolvedConstraint>& cs,
                                double t, GridFields& fields) {
  for (const ResolvedConstraint& c : cs) {
    if (!c.spec.active_at(t)) continue;
    for (std::size_t k = 0; k < c.nodes.size(); ++k) {
      const std::int64_t i = c.nodes[k];
      const auto u = static_cast<std::size_t>(i);
      if (!node_active(fields, u)) continue;
      common::Vec3 v = prescribed(grid, c.spec, i, t);
      if (c.spec.has_wall()) {
        // Momentum-stage correction of the projected velocity (enters L and the PIC share).
        const WallCorrection w = apply_wall_friction(fields.velocity[u], v, c.spec.wall);
        if (w.in_contact) {
          fields.wall_dv[u] += w.velocity - fields.velocity[u];
          fields.velocity[u] = w.velocity;
          fields.fixed[u] = static_cast<std::uint8_t>(fields.fixed[u] | (1u << c.spec.wall.axis));
        }
        continue;
      }
      if (!c.mirror.empty() && c.mirror[k] >= 0) {
        const auto mi = static_cast<std::size_t>(c.mirror[k]);
        v = 2.0 * v - (fields.is_active[mi] ? fields.velocity[mi] : v);
      }
      for (int d = 0; d < 3; ++d) {
        if (c.spec.fixed[static_cast<std::size_t>(d)]) {
          fields.velocity[u][d] = v[d];
          fields.fixed[u] = static_cast<std::uint8_t>(fields.fixed[u] | (1u << d));
        }
      }
    }
  }
}

void apply_acceleration_constraints(const Grid& grid, const std::vector<ResolvedConstraint>& cs,
                                    double t, double dt, GridFields& fields,
                                    std::vector<common::Vec3>* reactions) {
  if (reactions != nullptr) reactions->assign(cs.size(), common::Vec3::Zero());
  for (std::size_t ci = 0; ci < cs.size(); ++ci) {
    const ResolvedConstraint& c = cs[ci];
    if (!c.spec.active_at(t)) continue;
    common::Vec3 reaction = common::Vec3::Zero();
    for (std::size_t k = 0; k < c.nodes.size(); ++k) {
      const std::int64_t i = c.nodes[k];
      const auto u = static_cast<std::size_t>(i);
      if (!node_active(fields, u)) continue;
      const common::Vec3 a_before = fields.acceleration[u];
      if (c.spec.has_wall()) {
        // Contact on the trial velocity V(t) + a dt against the wall's velocity at t + dt.
        const common::Vec3 v_wall = prescribed(grid, c.spec, i, t + dt);
        const WallCorrection w =
            apply_wall_friction(fields.velocity[u] + dt * a_before, v_wall, c.spec.wall);
        if (w.in_contact) fields.acceleration[u] = (w.velocity - fields.velocity[u]) / dt;
      } else {
        common::Vec3 a = common::Vec3::Zero();
        if (c.spec.field)
          a = (c.spec.field(grid.node_position(i), t + dt) -
               c.spec.field(grid.node_position(i), t)) /
              dt;
        if (!c.mirror.empty() && c.mirror[k] >= 0) {
          const auto mi = static_cast<std::size_t>(c.mirror[k]);
          a = 2.0 * a - (fields.is_active[mi] ? fields.acceleration[mi] : a);
        }
        for (int d = 0; d < 3; ++d) {
          if (c.spec.fixed[static_cast<std::size_t>(d)]) fields.acceleration[u][d] = a[d];
        }
      }
      reaction += fields.mass[u] * (fields.acceleration[u] - a_before);
    }
    if (reactions != nullptr) (*reactions)[ci] = reaction;
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

std::vector<std::int64_t> face_points(const MaterialPoints& points, int axis, int side) {
  std::vector<std::int64_t> out;
  if (points.size() == 0) return out;
  const MaterialExtent e = material_extent(points);
  double hw_min = INFINITY;
  for (const common::Vec3& hw : points.half_width0) hw_min = std::min(hw_min, hw.minCoeff());
  const double face = side < 0 ? e.lo[axis] : e.hi[axis];
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double half = (points.F[p].cwiseAbs() * points.half_width0[p])[axis];
    const double edge = points.x[p][axis] + side * half;
    if (std::abs(edge - face) <= 1e-6 * hw_min) out.push_back(static_cast<std::int64_t>(p));
  }
  return out;
}

namespace {

/// Basis used for face loads: the grid functions (uGIMP's grid basis is the linear hat).
ShapeKind face_basis(ShapeKind kind) {
  return kind == ShapeKind::bspline2 ? ShapeKind::bspline2 : ShapeKind::linear;
}

/// The active nodes of `Shape`'s stencil at x (clipped, in cell units, to [margin, s_hi]) with
/// their weights: node_k and S_k, the first m entries. Returns the weights' sum.
template <class Shape, std::size_t K>
double gather_stencil(const Grid& grid, const GridFields& fields, const common::Vec3& x,
                      double margin, const std::array<double, 3>& s_hi,
                      std::array<std::int64_t, K>& node_k, std::array<double, K>& S_k, int& m) {
  constexpr int ns = Shape::support;
  std::array<int, 3> base{};
  std::array<std::array<double, ns>, 3> w{};
  for (int d = 0; d < 3; ++d) {
    const auto du = static_cast<std::size_t>(d);
    const double sd = std::clamp((x[d] - grid.origin[d]) / grid.spacing[d], margin, s_hi[du]);
    base[du] = Shape::stencil_base(sd, 0.0);
    for (int i = 0; i < ns; ++i)
      w[du][static_cast<std::size_t>(i)] = Shape::value(sd - (base[du] + i), 0.0);
  }
  m = 0;
  double sum = 0.0;
  for (int k = 0; k < ns; ++k) {
    for (int j = 0; j < ns; ++j) {
      for (int i = 0; i < ns; ++i) {
        const std::int64_t node = grid.node_index(base[0] + i, base[1] + j, base[2] + k);
        const double S = w[0][static_cast<std::size_t>(i)] * w[1][static_cast<std::size_t>(j)] *
                         w[2][static_cast<std::size_t>(k)];
        if (S == 0.0 || !fields.is_active[static_cast<std::size_t>(node)]) continue;
        sum += S;
        node_k[static_cast<std::size_t>(m)] = node;
        S_k[static_cast<std::size_t>(m)] = S;
        ++m;
      }
    }
  }
  return sum;
}

/// Forces of one traction load on its facets (Nanson area vectors, 2 x 2 Gauss points per
/// facet), distributed with the value-only weights of `Shape` (the stencil is computed once per
/// Gauss point and kept for the distribution pass). Returns the loaded (deformed) area [m^2].
template <class Shape>
double traction_on_facets(const Grid& grid, const TractionLoad& load, const MaterialPoints& points,
                          const std::vector<std::int64_t>& facet_points, bool reference_geometry,
                          GridFields& fields) {
  constexpr int ns = Shape::support;
  const int n = load.axis;
  const int t1 = (n + 1) % 3;
  const int t2 = (n + 2) % 3;
  common::Vec3 N = common::Vec3::Zero();
  N[n] = load.side;
  const double g = 1.0 / std::sqrt(3.0);
  // A Gauss point is clipped (in cell units) to where its stencil lies in the grid.
  const double margin = std::is_same_v<Shape, BSpline2Shape> ? 0.5 : 0.0;
  std::array<double, 3> s_hi{};
  for (int d = 0; d < 3; ++d)
    s_hi[static_cast<std::size_t>(d)] = std::nextafter(grid.cells[d] - margin, 0.0);
  std::array<std::int64_t, ns * ns * ns> node_k{};
  std::array<double, ns * ns * ns> S_k{};
  double area = 0.0;
  for (const std::int64_t slot : facet_points) {
    const auto p = static_cast<std::size_t>(slot);
    const common::Mat3& F = points.F[p];
    const common::Vec3& hw = points.half_width0[p];
    // Nanson: deformed area vector of the facet, reference area 4 hw_t1 hw_t2.
    const common::Vec3 a = F.determinant() * F.inverse().transpose() * N * (4.0 * hw[t1] * hw[t2]);
    const double a_norm = a.norm();
    area += a_norm;
    const common::Vec3 f = -load.pressure * a + load.traction * a_norm;
    // Where the facet lies on the grid: deformed, or (total Lagrangian) where it started.
    const common::Mat3 G = reference_geometry ? common::Mat3::Identity() : F;
    const common::Vec3 centre = points.x[p] + G.col(n) * (load.side * hw[n]);
    const common::Vec3 g1 = G.col(t1) * hw[t1];
    const common::Vec3 g2 = G.col(t2) * hw[t2];
    // The active nodes of the stencil at x with their weights (node_k, S_k, m); their sum.
    int m = 0;
    auto gather = [&](const common::Vec3& x) {
      return gather_stencil<Shape>(grid, fields, x, margin, s_hi, node_k, S_k, m);
    };
    for (const double alpha : {-g, g}) {
      for (const double beta : {-g, g}) {
        double sum = gather(centre + alpha * g1 + beta * g2);
        // A facet stretched or sheared far (a surface point by a footing's edge) may put a Gauss
        // point among nodes that hold no material: its share goes through the point itself.
        if (!(sum > 0.0)) sum = gather(points.x[p]);
        if (!(sum > 0.0)) {
          throw common::NumericalError("mpm traction load on axis " + std::to_string(n) + " side " +
                                       std::to_string(load.side) + ": the facet of point id " +
                                       std::to_string(points.id[p]) +
                                       " touches no node holding material");
        }
        for (int c = 0; c < m; ++c) {
          const auto cu = static_cast<std::size_t>(c);
          fields.force[static_cast<std::size_t>(node_k[cu])] += (0.25 * S_k[cu] / sum) * f;
        }
      }
    }
  }
  return area;
}

}  // namespace

double apply_traction(const Grid& grid, ShapeKind kind, const TractionLoad& load,
                      const MaterialPoints& points, const std::vector<std::int64_t>& facet_points,
                      GridFields& fields, bool reference_geometry) {
  if (load.axis < 0 || load.axis > 2 || (load.side != -1 && load.side != 1)) {
    throw common::InputError("mpm traction load: axis = " + std::to_string(load.axis) +
                             ", side = " + std::to_string(load.side) +
                             ": axis must be 0..2 and side -1 or +1");
  }
  // Facets use the grid basis: the linear hat (uGIMP's too) or the quadratic B-spline.
  if (face_basis(kind) == ShapeKind::bspline2) {
    return traction_on_facets<BSpline2Shape>(grid, load, points, facet_points, reference_geometry,
                                             fields);
  }
  return traction_on_facets<LinearShape>(grid, load, points, facet_points, reference_geometry,
                                         fields);
}

}  // namespace mpm
