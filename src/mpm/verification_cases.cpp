// Analytic verification set-ups (see header and docs/design/mpm.md, "Verification").
#include "mpm/verification_cases.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mpm/linear_elastic.hpp"

namespace mpm {
namespace {
using common::Mat3;
using common::Vec3;
}  // namespace

BarResult run_elastic_bar(ShapeKind shape, int cells, double periods, double cfl,
                          StressUpdate scheme, double pic_fraction) {
  const double length = 25.0, E = 100.0, rho = 1.0, v0 = 0.1;
  const double h = length / cells;
  SolverConfig cfg;
  cfg.grid = {Vec3(-2 * h, -1, -1), Vec3(h, 1, 1), common::Vec3i(cells + 4, 3, 3)};
  cfg.shape = shape;
  cfg.stress_update = scheme;
  cfg.flip = 1.0 - pic_fraction;
  cfg.cfl = cfl;
  LinearElastic material(E, 0.0, rho);
  MaterialPoints pts;
  Grid fill = cfg.grid;
  fill.spacing = Vec3(h, 1, 1);
  fill_box(pts, fill, Vec3::Zero(), Vec3(length, 1, 1), 2, rho, 0);
  // One point per cell laterally would do; 2 x 2 keeps fill_box uniform (lateral motion is off).
  const double beta = std::numbers::pi / (2 * length);
  for (std::size_t p = 0; p < pts.size(); ++p)
    pts.v[p] = Vec3(v0 * std::sin(beta * pts.x[p][0]), 0, 0);
  Solver solver(cfg, pts, {&material});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3::Constant(100), {false, true, true}, Vec3::Zero(), {}});
  // Fixed end: every node at x <= 0 (plain node fixing; see docs/design/mpm.md on B-splines).
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3(0, 100, 100), {true, false, false}, Vec3::Zero(), {}});

  BarResult r;
  r.period_analytic = 4 * length / std::sqrt(E / rho);
  auto energy = [&] {
    double e = 0;
    const MaterialPoints& q = solver.points();
    for (std::size_t p = 0; p < q.size(); ++p) {
      e += 0.5 * q.mass[p] * q.v[p].squaredNorm() +
           q.volume[p] * q.stress[p].squaredNorm() / (2 * E);
    }
    return e;
  };
  auto cm_velocity = [&] {
    double m = 0, mv = 0;
    const MaterialPoints& q = solver.points();
    for (std::size_t p = 0; p < q.size(); ++p) {
      m += q.mass[p];
      mv += q.mass[p] * q.v[p][0];
    }
    return mv / m;
  };
  r.energy_initial = energy();
  std::vector<double> crossings;
  double prev_v = cm_velocity(), prev_t = 0;
  while (solver.time() < periods * r.period_analytic) {
    solver.step();
    const double v = cm_velocity(), t = solver.time();
    if ((prev_v > 0) != (v > 0)) crossings.push_back(prev_t + (t - prev_t) * prev_v / (prev_v - v));
    prev_v = v;
    prev_t = t;
    r.energy_drift =
        std::max(r.energy_drift, std::abs(energy() - r.energy_initial) / r.energy_initial);
  }
  if (crossings.size() >= 2) {
    r.period =
        2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  }
  r.steps = solver.step_count();
  return r;
}

ColumnResult run_self_weight_column(ShapeKind shape, int cells, double transits,
                                    const ColumnOptions& options) {
  const double H = 1.0, rho = 1000.0, g = 10.0, E = options.young_modulus;
  const double h = H / cells;
  const bool plane = options.plane_strain;
  SolverConfig cfg;
  cfg.grid = {Vec3(-h, plane ? 0.0 : -h, -2 * h), Vec3::Constant(h),
              common::Vec3i(3, plane ? 1 : 3, cells + 4)};
  cfg.shape = shape;
  cfg.gravity = Vec3(0, 0, -g);
  cfg.damping = 0.3;
  cfg.cfl = 0.5;
  cfg.plane_strain_axis = plane ? 1 : -1;
  // A soft column falls through its first compression: the points move with the grid velocity,
  // which the held base constrains (with their own FLIP velocity the lowest cross it).
  cfg.grid_positions = E < 1e7;
  LinearElastic material(E, 0.0, rho);
  MaterialPoints pts;
  fill_box(pts, cfg.grid, Vec3::Zero(), Vec3(h, h, H), common::Vec3i(2, plane ? 1 : 2, 2), rho, 0);
  const std::vector<Vec3> X0 = pts.x;
  Solver solver(cfg, pts, {&material});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3::Constant(10), {true, true, false}, Vec3::Zero(), {}});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  const double c = material.wave_speed();
  const double t_end = transits * H / c;
  while (solver.time() < t_end) solver.step();

  ColumnResult r;
  r.cells = cells;
  r.steps = solver.step_count();
  const MaterialPoints& q = solver.points();
  double sum2 = 0, ke = 0;
  for (std::size_t p = 0; p < q.size(); ++p) {
    const double exact = -rho * g * (H - X0[p][2]);
    const double err = std::abs(q.stress[p](2, 2) - exact) / (rho * g * H);
    sum2 += err * err;
    r.max_error = std::max(r.max_error, err);
    ke += 0.5 * q.mass[p] * q.v[p].squaredNorm();
  }
  r.rms_error = std::sqrt(sum2 / static_cast<double>(q.size()));
  // Potential-energy scale of the static solution: (rho g H)^2 / (2E) * volume.
  const double volume = h * h * H;
  r.kinetic_ratio = ke / ((rho * g * H) * (rho * g * H) / (2 * E) * volume);
  return r;
}

TriaxialResult run_single_cell_triaxial(const TriaxialConfig& tc) {
  const int pad = tc.shape == ShapeKind::linear ? 0 : 1;
  SolverConfig cfg;
  cfg.grid = {Vec3::Constant(-pad), Vec3::Ones(), common::Vec3i::Constant(1 + 2 * pad)};
  cfg.shape = tc.shape;
  cfg.damping = tc.damping;
  cfg.cfl = tc.cfl;
  cfg.move_points = tc.move_points;
  cfg.formulation = tc.formulation;
  cfg.transfer = tc.transfer;
  const Mat3 s0 = -tc.pressure * Mat3::Identity() + tc.initial_stress_seed;
  LinearElastic material(tc.youngs_modulus, tc.poisson_ratio, tc.density, s0);
  MaterialPoints pts;
  fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), tc.points_per_cell, tc.density, 0);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    pts.stress[p] = s0;
    if (p < tc.offsets.size()) pts.x[p] += tc.offsets[p];
  }
  Solver solver(cfg, pts, {&material});
  const double v_top = -tc.inertial_number * std::sqrt(tc.pressure / tc.density);
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  solver.add_constraint(
      {Vec3(-10, -10, 1), Vec3::Constant(10), {false, false, true}, Vec3(0, 0, v_top), {}});
  for (int axis : {0, 1}) {
    for (int side : {-1, 1}) solver.add_traction({axis, side, tc.pressure, Vec3::Zero()});
  }
  if (tc.pin_rigid_modes) {
    // 3-2-1 support in the horizontal plane: node (0,0,0) fixed in x and y, node (1,0,0) in y.
    // Removes the rigid translations in x, y and the rotation about z; any homogeneous
    // deformation (which keeps (0,0,0) in place and (1,0,0) on the x axis) is left free.
    solver.add_constraint(node_constraint(cfg.grid, Vec3::Zero(), {true, true, false}));
    solver.add_constraint(node_constraint(cfg.grid, Vec3(1, 0, 0), {false, true, false}));
  }

  TriaxialResult r;
  double eps = 0;
  auto lateral_error = [&] {
    double e = 0;
    for (const Mat3& s : solver.points().stress) {
      e = std::max({e, std::abs(s(0, 0) / -tc.pressure - 1), std::abs(s(1, 1) / -tc.pressure - 1)});
    }
    return e;
  };
  while (-eps < tc.axial_strain) {
    const double dt = solver.next_dt();
    solver.step();
    double lzz = 0;
    for (const Mat3& L : solver.points().L) lzz += L(2, 2);
    eps += dt * lzz / static_cast<double>(solver.points().size());
    r.lateral_error = std::max(r.lateral_error, lateral_error());
  }
  r.lateral_error_end = lateral_error();
  r.axial_strain = eps;
  const double E = tc.youngs_modulus;
  const double axial_exact = -tc.pressure + E * eps;
  for (const Mat3& s : solver.points().stress) {
    r.axial_error = std::max(r.axial_error, std::abs(s(2, 2) - axial_exact) / std::abs(E * eps));
    r.mean_lateral += 0.5 * (s(0, 0) + s(1, 1)) / 8.0;
    r.mean_axial += s(2, 2) / 8.0;
  }
  r.steps = solver.step_count();
  const MaterialPoints& end = solver.points();
  for (std::size_t p = 0; p < end.size(); ++p) {
    for (std::size_t q = 0; q < pts.size(); ++q) {
      if (pts.id[q] == end.id[p])
        r.max_displacement = std::max(r.max_displacement, (end.x[p] - pts.x[q]).norm());
    }
  }
  return r;
}

}  // namespace mpm
