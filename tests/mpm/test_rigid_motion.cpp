// Verification: rigid translation keeps stress zero and momentum exact; a pre-stressed block in
// rigid rotation keeps its stress objective (sigma = R sigma_0 R^T).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Mat3;
using common::Vec3;

class RigidMotion : public ::testing::TestWithParam<mpm::ShapeKind> {};

// Dyadic set-up (h = 1/4, points at 1/4 and 3/4 of cells, v and dt powers of two): every weight,
// nodal velocity and position is exact in binary, so the nodal velocities equal v exactly, L is
// exactly zero and so is the stress; momentum is exactly conserved. (With arbitrary numbers the
// same holds to round-off, ~1e-16 relative in L.)
TEST_P(RigidMotion, TranslationKeepsStressExactlyZeroAndMomentumExact) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.25), common::Vec3i(16, 12, 12)};
  cfg.shape = GetParam();
  cfg.dt = 1.0 / 1024;
  mpm::LinearElastic mat(1e6, 0.3, 1000.0);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3(0.5, 0.5, 0.5), Vec3(1.5, 1.25, 1.25), 2, 1000.0, 0);
  const Vec3 v(1.0, -0.5, 0.25);
  for (auto& vp : pts.v) vp = v;
  mpm::Solver s(cfg, pts, {&mat});
  Vec3 p0 = Vec3::Zero();
  for (std::size_t p = 0; p < pts.size(); ++p) p0 += pts.mass[p] * pts.v[p];
  s.run(200);
  Vec3 p1 = Vec3::Zero();
  for (std::size_t p = 0; p < s.points().size(); ++p) {
    EXPECT_EQ(s.points().stress[p], Mat3::Zero());
    EXPECT_EQ(s.points().v[p], v);
    EXPECT_EQ(s.points().volume[p], pts.volume[p]);
    p1 += s.points().mass[p] * s.points().v[p];
    EXPECT_EQ(s.points().x[p], pts.x[p] + 200 * cfg.dt * v);
  }
  EXPECT_EQ(p1, p0);
}

// Block pre-stressed with sigma_0, all grid nodes driven by the rigid rotation field
// v = w x (x - c) (points start on it, PIC update so they follow it). L = W to round-off, so the
// Hughes-Winget update rotates the stress by 2 atan(w dt / 2) per step: after a quarter turn the
// stress must equal R sigma_0 R^T with R the accumulated rotation. Tolerance 1e-8 relative:
// round-off in L (~1e-15 / step) times E dt over ~1600 steps gives < 1e-10 of |sigma_0|.
// Against the exact angle w t the phase error is n (w dt)^3 / 12 = 1.3e-7 rad: 1e-6 relative.
TEST_P(RigidMotion, RotationKeepsPrestressObjective) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3(-2, -2, -1), Vec3::Constant(0.25), common::Vec3i(16, 16, 8)};
  cfg.shape = GetParam();
  cfg.dt = 1e-3;
  cfg.flip = 0.0;  // PIC
  Mat3 s0;
  s0 << -100e3, 20e3, 5e3, 20e3, -50e3, 0, 5e3, 0, -80e3;
  mpm::LinearElastic mat(1e7, 0.3, 1000.0, s0);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3(-0.5, -0.25, -0.25), Vec3(0.5, 0.25, 0.25), 2, 1000.0, 0);
  const double w = 1.0;
  const Vec3 axis = Vec3::UnitZ();
  for (std::size_t p = 0; p < pts.size(); ++p) {
    pts.v[p] = w * axis.cross(pts.x[p]);
    pts.stress[p] = s0;
  }
  mpm::Solver s(cfg, pts, {&mat});
  mpm::VelocityConstraint rot{cfg.grid.origin,
                              cfg.grid.upper(),
                              {true, true, true},
                              Vec3::Zero(),
                              [&](const Vec3& x, double) { return Vec3(w * axis.cross(x)); }};
  s.add_constraint(rot);
  const int n = 1571;  // w t ~ pi / 2
  s.run(n);
  const double angle = n * 2 * std::atan(0.5 * w * cfg.dt);
  const Mat3 R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  const Mat3 expected = R * s0 * R.transpose();
  const Mat3 R_exact = Eigen::AngleAxisd(w * s.time(), axis).toRotationMatrix();
  const Mat3 expected_exact = R_exact * s0 * R_exact.transpose();
  for (const Mat3& sp : s.points().stress) {
    EXPECT_LT((sp - expected).norm(), 1e-8 * s0.norm());
    EXPECT_LT((sp - expected_exact).norm(), 1e-6 * s0.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, RigidMotion,
                         ::testing::Values(mpm::ShapeKind::linear, mpm::ShapeKind::ugimp,
                                           mpm::ShapeKind::bspline2),
                         [](const auto& param_info) {
                           return std::string(mpm::to_string(param_info.param));
                         });

}  // namespace
