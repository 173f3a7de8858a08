// Verification of quasi-static mass scaling (SolverConfig::mass_scaling, docs/design/mpm.md "Mass
// scaling"): the elastic triaxial of jobs/elastic_triaxial.toml gives the unscaled answer in fewer
// steps, and a column under gravity keeps its real weight.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/errors.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Mat3;
using common::Vec3;

struct Triaxial {
  double sigma_zz = 0.0;   ///< mean point sigma_zz at the end [Pa]
  double sigma_lat = 0.0;  ///< mean point sigma_xx, sigma_yy at the end [Pa]
  double eps = 0.0;        ///< sum dt mean(L_zz) [-]
  double max_ratio = 0.0;  ///< largest E_kin / W_int from 5 % of the run on [-]
  double dt = 0.0;         ///< first time step [s]
  mpm::Energies end;       ///< energies at the end
  std::int64_t steps = 0;
};

/// jobs/elastic_triaxial.toml as a Solver: one 1 m cell, 8 points, E = 50 MPa, nu = 0.3,
/// rho = 1696 kg/m^3, from -100 kPa I, 100 kPa on the x and y faces, bottom held in z, top at
/// -1 mm/s, 3-2-1 support of two bottom nodes, damping 0.2; to 1 % axial strain (10 s).
Triaxial triaxial(double mass_scaling) {
  const double E = 50e6, nu = 0.3, rho = 1696.0, p = 100e3;
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  cfg.damping = 0.2;
  cfg.mass_scaling = mass_scaling;
  const Mat3 s0 = -p * Mat3::Identity();
  mpm::LinearElastic material(E, nu, rho, s0);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), 2, rho, 0);
  for (Mat3& s : pts.stress) s = s0;
  mpm::Solver solver(cfg, pts, {&material});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  solver.add_constraint(
      {Vec3(-10, -10, 1), Vec3::Constant(10), {false, false, true}, Vec3(0, 0, -1e-3), {}});
  solver.add_constraint(mpm::node_constraint(cfg.grid, Vec3::Zero(), {true, true, false}));
  solver.add_constraint(mpm::node_constraint(cfg.grid, Vec3(1, 0, 0), {false, true, false}));
  for (int axis : {0, 1}) {
    for (int side : {-1, 1}) solver.add_traction({axis, side, p, Vec3::Zero()});
  }
  const double end_time = 10.0;
  mpm::QuasiStaticWatch watch(cfg.quasi_static_ratio, mass_scaling, end_time);
  Triaxial r;
  r.dt = solver.next_dt();
  while (solver.time() < end_time * (1 - 1e-12)) {
    const double dt = solver.next_dt();
    solver.step();
    double lzz = 0.0;
    for (const Mat3& L : solver.points().L) lzz += L(2, 2);
    r.eps += dt * lzz / 8.0;
    const std::string w = watch.observe(solver.step_count(), solver.time(), solver.energies());
    EXPECT_TRUE(w.empty()) << w;
  }
  for (const Mat3& s : solver.points().stress) {
    r.sigma_zz += s(2, 2) / 8.0;
    r.sigma_lat += 0.5 * (s(0, 0) + s(1, 1)) / 8.0;
  }
  r.max_ratio = watch.max_ratio();
  r.end = solver.energies();
  r.steps = solver.step_count();
  return r;
}

// The quasi-static answer with s = 100 within 1 % of the unscaled one (measured 9e-4): the axial
// stress increment sigma_zz + p (1 % of it), the lateral stress (1 % of p, measured 0.24 %) and
// the axial strain, at the same end time; in fewer steps: the CFL step grows by sqrt(100) = 10
// (within 1 %: the speed is c / sqrt(s) + |v|max, |v|max ~ 1 mm/s against c ~ 200 m/s). The run
// stays quasi-static: E_kin / W_int below the default threshold 0.01 from 5 % of the run on
// (measured 1.5e-3; 1.4e-5 unscaled), and the internal work (the stored elastic energy plus the
// work against the confinement) is the unscaled one within 1 % (measured 0.2 %).
TEST(MassScaling, ElasticTriaxialGivesUnscaledAnswerInFewerSteps) {
  const Triaxial a = triaxial(1.0);
  const Triaxial b = triaxial(100.0);
  const double p = 100e3;
  std::printf(
      "triaxial s = 1: %lld steps, dt %.4g s, sigma_zz %.1f Pa, sigma_lat %.1f Pa, eps %.5f, max "
      "E_kin/W_int %.3g, end %.3g (W_int %.4g J)\n",
      static_cast<long long>(a.steps), a.dt, a.sigma_zz, a.sigma_lat, a.eps, a.max_ratio,
      a.end.ratio(), a.end.internal_work);
  std::printf(
      "triaxial s = 100: %lld steps, dt %.4g s, sigma_zz %.1f Pa, sigma_lat %.1f Pa, eps %.5f, "
      "max E_kin/W_int %.3g, end %.3g (W_int %.4g J); error of sigma_zz + p %.3e\n",
      static_cast<long long>(b.steps), b.dt, b.sigma_zz, b.sigma_lat, b.eps, b.max_ratio,
      b.end.ratio(), b.end.internal_work, std::abs(b.sigma_zz - a.sigma_zz) / (a.sigma_zz + p));
  EXPECT_NEAR(b.sigma_zz + p, a.sigma_zz + p, 0.01 * std::abs(a.sigma_zz + p));
  EXPECT_NEAR(b.sigma_lat, a.sigma_lat, 0.01 * p);
  EXPECT_NEAR(b.eps, a.eps, 0.01 * std::abs(a.eps));
  EXPECT_LT(b.steps, a.steps / 5);
  EXPECT_NEAR(b.dt / a.dt, 10.0, 0.01);
  EXPECT_LT(b.max_ratio, 0.01);
  EXPECT_NEAR(b.end.internal_work, a.end.internal_work, 0.01 * a.end.internal_work);
  EXPECT_GT(a.end.internal_work, 0.0);
  // Kinetic energy scales with s at the same velocities.
  EXPECT_GT(b.end.kinetic, a.end.kinetic);
}

/// Elastic column, H = 1 m in 8 cells of 0.125 m, rho = 1000 kg/m^3, g = 10 m/s^2, E = 1e7 Pa,
/// nu = 0, lateral velocities held, bottom held, damping 0.3, for 60 wave transits (in steps: the
/// same count for every s, the wave being sqrt(s) slower and the step sqrt(s) longer).
mpm::MaterialPoints column(double mass_scaling, std::int64_t& steps) {
  const double H = 1.0, rho = 1000.0, g = 10.0, E = 1e7;
  const int cells = 8;
  const double h = H / cells;
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3(-h, -h, -2 * h), Vec3::Constant(h), common::Vec3i(3, 3, cells + 4)};
  cfg.gravity = Vec3(0, 0, -g);
  cfg.damping = 0.3;
  cfg.mass_scaling = mass_scaling;
  mpm::LinearElastic material(E, 0.0, rho);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3(h, h, H), 2, rho, 0);
  mpm::Solver solver(cfg, pts, {&material});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3::Constant(10), {true, true, false}, Vec3::Zero(), {}});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  const double t_end = 60.0 * H / (material.wave_speed() / std::sqrt(mass_scaling));
  while (solver.time() < t_end) solver.step();
  steps = solver.step_count();
  return solver.points();
}

// With linear shapes and 2 points per cell both points of a cell carry the stress of the cell
// centre (test_self_weight_column.cpp): sigma_zz = -rho g (H - Z_c) at rest. With s = 100 the
// column keeps its real weight: every point within 0.5 % of rho g H of that (a weight scaled
// with the inertia would be 100 x), and the base stress extrapolated from the bottom cell,
// sigma_zz(bottom cell) - rho g h / 2, is rho g H within 0.5 %.
TEST(MassScaling, GravityColumnKeepsItsWeight) {
  const double H = 1.0, rho = 1000.0, g = 10.0, h = 0.125;
  std::int64_t steps = 0;
  const mpm::MaterialPoints q = column(100.0, steps);
  double worst = 0.0;
  double bottom = 0.0;
  int n_bottom = 0;
  for (std::size_t p = 0; p < q.size(); ++p) {
    const double z_c = h * (std::floor(q.x[p][2] / h) + 0.5);
    worst = std::max(worst, std::abs(q.stress[p](2, 2) + rho * g * (H - z_c)) / (rho * g * H));
    if (q.x[p][2] < h) {
      bottom += q.stress[p](2, 2);
      ++n_bottom;
    }
    EXPECT_DOUBLE_EQ(q.mass[p], rho * h * h * H / static_cast<double>(q.size()));
  }
  const double base = bottom / n_bottom - rho * g * h / 2;
  std::printf(
      "column s = 100: %lld steps, worst point error %.3e of rho g H, base %.1f Pa (rho g "
      "H = %.1f Pa)\n",
      static_cast<long long>(steps), worst, base, rho * g * H);
  EXPECT_LT(worst, 0.005);
  EXPECT_NEAR(-base, rho * g * H, 0.005 * rho * g * H);
}

TEST(MassScaling, BelowOneIsRefused) {
  mpm::SolverConfig cfg;
  cfg.mass_scaling = 0.5;
  try {
    cfg.validate();
    FAIL() << "mass_scaling = 0.5 was accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mpm.mass_scaling = 0.5"), std::string::npos) << e.what();
  }
}

}  // namespace
