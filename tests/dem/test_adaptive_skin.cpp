// The adaptive Verlet skin (dem/adaptive_skin.hpp, dem.numerics.verlet_skin_min): the choice
// against its cost model written out here; a slow cell thins its skin and keeps its stress; a
// fast one widens it again; 1 and 2 threads and a save/load in between give the same bits.
#include "dem/adaptive_skin.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "common/state_store.hpp"
#include "dem/loading.hpp"
#include "dem/rve.hpp"
#include "dem/simulation.hpp"
#include "dem/state.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Mat3;
using common::Vec3;

dem::SkinInputs inputs(double measure, std::int64_t steps) {
  dem::SkinInputs in;
  in.measure = measure;
  in.skin = 1e-5;
  in.steps = steps;
  in.shell_pairs = 300;
  in.spheres = 1000;
  in.lo = 3e-6;
  in.hi = 1e-5;
  return in;
}

TEST(AdaptiveSkin, OptimalSkinFollowsTheCostModel) {
  // k = 300 shell pairs / (1000 spheres 1e-5 m) = 3e4 per sphere per metre; a measure of
  // 4e-6 m in 400 steps: v = 1e-8 m a step; s* = sqrt(R v / k).
  const dem::SkinInputs in = inputs(4e-6, 400);
  const double expected = std::sqrt(dem::kRebuildPairCost * 1e-8 / 3e4);
  ASSERT_GT(expected, in.lo);
  ASSERT_LT(expected, in.hi);
  EXPECT_NEAR(dem::optimal_skin(in), expected, 1e-12 * expected);
  // Clamped: a cell at rest takes the thinnest skin, a fast one the widest.
  EXPECT_EQ(dem::optimal_skin(inputs(0.0, 400)), in.lo);
  EXPECT_EQ(dem::optimal_skin(inputs(1e-5, 1)), in.hi);
  // No pair outside contact: nothing to save, the widest skin.
  dem::SkinInputs none = in;
  none.shell_pairs = 0;
  EXPECT_EQ(dem::optimal_skin(none), in.hi);
  // A drift that is not finite (a position that is not: the rebuild names it): the widest skin.
  EXPECT_EQ(dem::optimal_skin(inputs(std::numeric_limits<double>::infinity(), 10)), in.hi);
}

TEST(AdaptiveSkin, RebuildsWhenDueAndEarlyOnlyToShrinkAfterMinSteps) {
  // Due: the measure reached the skin.
  const dem::SkinDecision due = dem::decide_skin(inputs(1e-5, 30));
  EXPECT_TRUE(due.rebuild);
  EXPECT_EQ(due.skin, dem::optimal_skin(inputs(1e-5, 30)));
  EXPECT_TRUE(dem::decide_skin(inputs(std::nan(""), 30)).rebuild);
  // Barely moving: not before kSkinMinSteps, then with the thin skin.
  EXPECT_FALSE(dem::decide_skin(inputs(1e-9, dem::kSkinMinSteps - 1)).rebuild);
  const dem::SkinDecision early = dem::decide_skin(inputs(1e-9, dem::kSkinMinSteps));
  EXPECT_TRUE(early.rebuild);
  EXPECT_EQ(early.skin, 3e-6);
  // Moving enough that the optimum is above half the skin: the list is kept.
  dem::SkinInputs moving = inputs(8e-6, 400);
  ASSERT_GE(dem::optimal_skin(moving), 0.5 * moving.skin);
  EXPECT_FALSE(dem::decide_skin(moving).rebuild);
}

dem::Simulation slow_cell(double skin_min) {
  dem::Numerics num;
  num.skin_min_factor = skin_min;
  dem::Simulation sim =
      dem::make_simulation(dem_test::reference_packing(), dem_test::reference_material(), num);
  sim.cell().l(2, 2) = -6.0;  // about I = 2.5e-4 (the paper's quasi-static rate)
  sim.cell().l(0, 0) = sim.cell().l(1, 1) = 3.0;
  return sim;
}

double pressure(const dem::Simulation& s) { return -s.stress().trace() / 3.0; }

bool same_state(const dem::Simulation& a, const dem::Simulation& b) {
  common::StateStore sa;
  common::StateStore sb;
  dem::save_simulation(a, sa);
  dem::save_simulation(b, sb);
  return sa.fields() == sb.fields();
}

// A cell strained at the quasi-static rate moves far less than its skin allows: it rebuilds
// early with the thinnest skin, keeps fewer pairs, and its stress is the fixed skin's (the skin
// changes no physics: the only difference is the round-off of wrapping positions at a build).
TEST(AdaptiveSkin, SlowCellThinsItsSkinAndKeepsItsStress_threads_1_2) {
  omp_set_num_threads(1);
  dem::Simulation fixed = slow_cell(0.0);
  dem::Simulation thin = slow_cell(0.03);
  const int steps = 1500;
  for (int k = 0; k < steps; ++k) {
    fixed.step();
    thin.step();
  }
  const double r_max = thin.verlet().r_max;
  EXPECT_EQ(fixed.verlet().skin, 0.1 * r_max);
  EXPECT_EQ(thin.verlet().skin, 0.03 * r_max);
  EXPECT_GT(thin.verlet().builds, fixed.verlet().builds);
  EXPECT_LT(static_cast<double>(thin.contacts().size()),
            0.9 * static_cast<double>(fixed.contacts().size()));
  const double p = pressure(fixed);
  ASSERT_GT(p, 1e4);
  EXPECT_LT((thin.stress() - fixed.stress()).cwiseAbs().maxCoeff(), 1e-8 * p);

  // 2 threads, and a save/load before the early build (the list's age is state), give the
  // same bits.
  omp_set_num_threads(2);
  dem::Simulation two = slow_cell(0.03);
  ASSERT_GT(two.spheres().size(), 512u);  // above the threshold of the parallel region
  const int saved_at = 50;
  ASSERT_LT(saved_at, dem::kSkinMinSteps);
  for (int k = 0; k < saved_at; ++k) two.step();
  common::StateStore mid;
  dem::save_simulation(two, mid);
  dem::Simulation back = dem::load_simulation(mid);
  for (int k = saved_at; k < steps; ++k) back.step();
  EXPECT_TRUE(same_state(back, thin));
  omp_set_num_threads(omp_get_num_procs());
}

// The same cell then sheared fast, its spheres moving at about 1 m/s: the lists are due after a
// few steps and the skin widens back to where a build pays (the model's optimum here is about
// 0.06 r_max, as for the reference packing sheared at I = 1e-2: docs/design/dem.md).
TEST(AdaptiveSkin, FastCellWidensItsSkin) {
  dem::Simulation sim = slow_cell(0.03);
  for (int k = 0; k < 300; ++k) sim.step();
  const double r_max = sim.verlet().r_max;
  ASSERT_EQ(sim.verlet().skin, 0.03 * r_max);
  sim.cell().l = Mat3::Zero();
  sim.cell().l(2, 2) = -50.0;
  sim.cell().l(0, 1) = 20.0;
  auto& u = sim.spheres().u;
  for (std::size_t q = 0; q < u.size(); ++q) {
    const auto t = static_cast<double>(q);
    u[q] = Vec3(std::sin(t), std::cos(1.7 * t), std::sin(2.3 * t));
  }
  const std::int64_t builds = sim.verlet().builds;
  double widest = 0.0;
  for (int k = 0; k < 300; ++k) {
    sim.step();
    widest = std::max(widest, sim.verlet().skin);
  }
  EXPECT_GT(sim.verlet().builds, builds + 2);
  EXPECT_GT(widest, 0.05 * r_max);
  EXPECT_LE(widest, 0.1 * r_max);
}

// The preparation runs with the fixed skin: an RVE equilibrated with the adaptive skin asked for
// is the same, bit for bit, as one without (a compaction is chaotic: the round-off of another
// list history would give another sample), and switches to the adaptive skin afterwards.
TEST(AdaptiveSkin, PreparationKeepsTheFixedSkin) {
  dem::RveParams p;
  p.material = dem_test::reference_material();
  p.initial_pressure = 1.5e5;  // the reference packing is at 1e5 Pa: some steps of servo
  p.numerics.skin_min_factor = 0.0;
  const dem::Rve fixed(dem_test::reference_packing(), p);
  p.numerics.skin_min_factor = 0.03;
  const dem::Rve adaptive(dem_test::reference_packing(), p);
  ASSERT_GT(fixed.simulation().steps(), 100);
  EXPECT_EQ(fixed.simulation().steps(), adaptive.simulation().steps());
  const auto& a = fixed.simulation().spheres().x;
  const auto& b = adaptive.simulation().spheres().x;
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
  EXPECT_EQ(fixed.simulation().numerics().skin_min_factor, 0.0);
  EXPECT_EQ(adaptive.simulation().numerics().skin_min_factor, 0.03);
  // and from_simulation switches a prepared simulation's skin to the RVE's
  const dem::Rve from = dem::Rve::from_simulation(fixed.simulation(), p);
  EXPECT_EQ(from.simulation().numerics().skin_min_factor, 0.03);
}

}  // namespace
