// The energy-growth guard: its rule on a made-up balance, and on real solvers: a time step above
// the stability limit trips it (naming the step, the time and the fastest point), a stable block
// settling under gravity on a base does not (USF and MUSL), and a released pre-stress does not.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "mpm/benchmark.hpp"
#include "mpm/boundary.hpp"
#include "mpm/energy_guard.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Vec3;

TEST(EnergyGuardRule, ABalancedSceneNeverTrips) {
  mpm::EnergyGuard g(0.5);
  g.start(0.0, 0.0);
  // Gravity puts 1 J per step in; half goes to motion, half to the material.
  for (int k = 1; k <= 1000; ++k) EXPECT_FALSE(g.observe(0.5 * k, 0.5 * k, 1.0));
  EXPECT_NEAR(g.created(), 0.0, 1e-9);
  EXPECT_LT(g.max_share(), 1e-12);
}

TEST(EnergyGuardRule, MotionFromNothingTripsAfterThePersistence) {
  mpm::EnergyGuard g(0.5);
  g.start(1.0, 0.0);
  int tripped_at = -1;
  double kin = 1.0;
  for (int k = 1; k <= 100 && tripped_at < 0; ++k) {
    kin *= 1.5;  // an unstable mode: no work in, kinetic energy grows geometrically
    if (g.observe(kin, 0.0, 0.0)) tripped_at = k;
  }
  // created / scale = (kin - 1) / kin > 0.5 from k = 2 on: 10 steps in a row end at k = 11.
  EXPECT_EQ(tripped_at, 1 + mpm::EnergyGuard::kPersist);
  EXPECT_GT(g.max_share(), 0.5);
}

// The drift the log warns of: a balance that holds more than kDriftWarn of its scale for the
// persistence, in the materials' work (which the rule leaves alone) or in motion; a balanced
// scene and a short burst stay below it.
TEST(EnergyGuardRule, DriftIsTheBalanceHeldInAnyForm) {
  mpm::EnergyGuard g(0.5);
  g.start(0.0, 0.0);
  // The materials take 1.3 times the work put in: created / scale = 0.3 / 1.3.
  for (int k = 1; k <= 1000; ++k) EXPECT_FALSE(g.observe(1e-3, 1.3 * k, 1.0));
  EXPECT_NEAR(g.drift(), (0.3 * 991 + 1e-3) / (1.3 * 991), 1e-3);  // the oldest of the last 10
  EXPECT_GT(g.drift(), mpm::EnergyGuard::kDriftWarn);
  EXPECT_EQ(g.max_share(), 0.0);  // not motion: the stopping rule stays at 0
  mpm::EnergyGuard b(0.5);
  b.start(0.0, 0.0);
  for (int k = 1; k <= 50; ++k) EXPECT_FALSE(b.observe(1e-3, 0.999 * k, 1.0));
  EXPECT_LT(b.max_drift(), 0.01);
  mpm::EnergyGuard h(0.5);
  h.start(0.0, 0.0);
  // A burst shorter than the persistence, then the materials' work back to the work put in.
  for (int k = 1; k < mpm::EnergyGuard::kPersist; ++k) EXPECT_FALSE(h.observe(0.0, 10.0 * k, 1.0));
  for (int k = 1; k <= 50; ++k) EXPECT_FALSE(h.observe(0.0, 9.0 + k, 1.0));
  EXPECT_LT(h.max_drift(), mpm::EnergyGuard::kDriftWarn);
  // A run's first steps: a balance of some steps' work is a large share of a scale that is only
  // a few tens of steps' work itself (half of it at step 27 on a spared footing); not a drift.
  mpm::EnergyGuard s(0.5);
  s.start(0.0, 0.0);
  for (int k = 1; k <= 60; ++k) EXPECT_FALSE(s.observe(1e-3, std::min(k + 14.0, 2.0 * k), 1.0));
  EXPECT_EQ(s.max_drift(), 0.0);
}

TEST(EnergyGuardRule, ADriftWithoutMotionOrAShortBurstDoesNotTrip) {
  mpm::EnergyGuard g(0.5);
  g.start(0.0, 0.0);
  // The materials' work drifts above the work put in while the points hardly move.
  for (int k = 1; k <= 200; ++k) EXPECT_FALSE(g.observe(1e-3, 2.0 * k, 1.0));
  mpm::EnergyGuard h(0.5);
  h.start(0.0, 0.0);
  // A burst of kinetic energy for fewer steps than the persistence, then back to the balance.
  for (int k = 1; k < mpm::EnergyGuard::kPersist; ++k) EXPECT_FALSE(h.observe(10.0 + k, 0.0, 0.0));
  for (int k = 1; k <= 50; ++k) EXPECT_FALSE(h.observe(1.0, 0.0, 1.0));
  mpm::EnergyGuard off(0.0);
  off.start(1.0, 0.0);
  double kin = 1.0;
  for (int k = 1; k <= 50; ++k) EXPECT_FALSE(off.observe(kin *= 2.0, 0.0, 0.0));
}

mpm::SolverConfig block_config() {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.25), common::Vec3i(6, 6, 8)};
  cfg.shape = mpm::ShapeKind::linear;
  cfg.cfl = 0.5;
  return cfg;
}

mpm::MaterialPoints block(const mpm::Grid& g) {
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, g, Vec3(0.25, 0.25, 0.25), Vec3(1.25, 1.0, 1.5), 2, 1800.0, 0);
  return pts;
}

TEST(EnergyGuard, ATimeStepAboveTheStabilityLimitStopsTheRunNamingStepTimeAndPoint) {
  mpm::SolverConfig cfg = block_config();
  mpm::LinearElastic mat(1e5, 0.3, 1800.0);  // h / (c + v) = 0.026 s
  cfg.dt = 0.055;                            // 2.1x the limit: a growth over tens of steps
  cfg.refuse_unstable_dt = false;
  mpm::MaterialPoints pts = block(cfg.grid);
  for (std::size_t p = 0; p < pts.size(); ++p) pts.v[p] = Vec3(0, 0, 1e-3 * (p % 3 == 0 ? 1 : -1));
  mpm::Solver s(cfg, pts, {&mat});
  std::string what;
  std::int64_t at = -1;
  try {
    s.run(200);
  } catch (const common::NumericalError& e) {
    what = e.what();
    at = s.step_count();
  }
  ASSERT_FALSE(what.empty()) << "the unstable run was not stopped";
  EXPECT_NE(what.find("the energy grows without a source"), std::string::npos) << what;
  EXPECT_NE(what.find("mpm step "), std::string::npos);
  EXPECT_NE(what.find("fastest point is id"), std::string::npos);
  EXPECT_NE(what.find("mpm.energy_guard = 0"), std::string::npos);
  EXPECT_GE(at, mpm::EnergyGuard::kPersist);
  // Off, the same run goes on until another guard (a volume, a point leaving the grid) or
  // the doubles give way: the energy guard stopped it first, on the energy.
  cfg.energy_guard = 0.0;
  mpm::Solver off(cfg, pts, {&mat});
  try {
    off.run(at);
  } catch (const common::NumericalError& e) {
    EXPECT_EQ(std::string(e.what()).find("the energy grows"), std::string::npos);
  }
}

TEST(EnergyGuard, AStableBlockSettlingOnABaseUnderGravityDoesNotTrip) {
  for (const mpm::StressUpdate scheme : {mpm::StressUpdate::usf, mpm::StressUpdate::musl}) {
    mpm::SolverConfig cfg = block_config();
    cfg.stress_update = scheme;
    cfg.gravity = Vec3(0, 0, -9.81);
    cfg.damping = 0.05;
    cfg.flip = 0.95;
    cfg.grid_positions = true;  // the points move with the grid, which the base holds
    mpm::LinearElastic mat(1e6, 0.3, 1800.0);
    mpm::MaterialPoints pts = block(cfg.grid);
    mpm::Solver s(cfg, pts, {&mat});
    mpm::VelocityConstraint base;  // the node planes under the block, held vertically
    base.name = "base";
    base.lo = Vec3(-1.0, -1.0, -1.0);
    base.hi = Vec3(10.0, 10.0, 0.3);
    base.fixed = {false, false, true};
    s.add_constraint(base);
    EXPECT_NO_THROW(s.run(400));
    const mpm::EnergyGuard& g = s.energy_guard();
    // Gravity's work went into the material and the motion, the damping took some.
    EXPECT_GT(g.external_work(), 0.0);
    EXPECT_LT(g.max_share(), 0.1) << "max share " << g.max_share();
  }
}

TEST(EnergyGuard, AReleasedPreStressDoesNotTrip) {
  mpm::SolverConfig cfg = block_config();
  // A compressed block let go: its stored elastic energy becomes motion (no work in).
  const common::Mat3 pre = -1e3 * common::Mat3::Identity();
  mpm::LinearElastic mat(1e5, 0.3, 1800.0, pre);
  mpm::MaterialPoints pts = block(cfg.grid);
  for (std::size_t p = 0; p < pts.size(); ++p) pts.stress[p] = pre;
  mpm::Solver s(cfg, pts, {&mat});
  EXPECT_NO_THROW(s.run(300));
  EXPECT_LT(s.energy_guard().max_share(), 0.5);
  EXPECT_GT(s.energies().kinetic, 0.0);
}

}  // namespace
