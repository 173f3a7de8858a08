// Unit tests of the rebalancing policy (farm/rebalance.hpp): no migration on timing noise, one
// migration on a real change of cost.
#include <gtest/gtest.h>

#include <random>

#include "farm/rebalance.hpp"

namespace {

/// 8 RVEs at the points of a 2x2x2 arrangement inside one grid cell (the paper's job).
farm::RveGraph one_cell_graph() {
  const mpm::Grid g{common::Vec3::Zero(), common::Vec3::Ones(), common::Vec3i(1, 1, 1)};
  std::vector<common::Vec3> x;
  for (int k = 0; k < 8; ++k)
    x.emplace_back(0.25 + 0.5 * (k & 1), 0.25 + 0.5 * ((k >> 1) & 1), 0.25 + 0.5 * (k >> 2));
  return farm::cell_graph(g, x);
}

/// Runs `windows` checks of 8 RVEs with costs base[k] * (1 + noise * u), u uniform in [-1, 1], from
/// the METIS partition of `base`; returns the number of migrations. `change` is applied to the base
/// costs at window `at`.
int migrations(double decay, double noise, int windows, std::vector<double> base,
               const std::vector<double>& change = {}, int at = -1,
               std::vector<int>* final_owner = nullptr) {
  const farm::RveGraph g = one_cell_graph();
  std::vector<int> owner = farm::partition_metis(g, base, 2, 1);
  farm::CostAverage avg(decay);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int moved = 0;
  for (int w = 0; w < windows; ++w) {
    if (w == at) base = change;
    std::vector<double> window(base.size());
    for (std::size_t k = 0; k < base.size(); ++k) window[k] = base[k] * (1.0 + noise * u(rng));
    avg.add_window(window);
    const farm::RebalancePlan plan = farm::plan_rebalance(g, owner, avg.cost(), 2, 1.05, 1);
    if (plan.migrate) {
      ++moved;
      owner = plan.owner;
    }
  }
  if (final_owner != nullptr) *final_owner = owner;
  return moved;
}

}  // namespace

// Identical RVEs timed with +/-15 % noise per window: deciding on single windows (decay 0, the old
// policy) migrates again and again; the averaged costs never do.
TEST(Rebalance, IdenticalRvesWithTimingNoiseDoNotMigrate) {
  const std::vector<double> equal(8, 1.0);
  EXPECT_GT(migrations(0.0, 0.15, 3000, equal), 50);
  EXPECT_EQ(migrations(0.8, 0.15, 3000, equal), 0);
}

// One RVE becomes 3x as expensive (it gained contacts): the imbalance 6/5 = 1.2 is removed by one
// migration within a few windows, and nothing moves after that.
TEST(Rebalance, RealCostChangeMigratesOnce) {
  std::vector<double> changed(8, 1.0);
  changed[0] = 3.0;
  std::vector<int> owner;
  EXPECT_EQ(migrations(0.8, 0.05, 500, std::vector<double>(8, 1.0), changed, 100, &owner), 1);
  EXPECT_LT(farm::imbalance(owner, changed, 2), 1.05);
}

TEST(Rebalance, CostAverageWeighsRecentWindowsMore) {
  farm::CostAverage avg(0.5);
  EXPECT_TRUE(avg.cost().empty());
  avg.add_window({1.0, 2.0});
  EXPECT_EQ(avg.cost(), (std::vector<double>{1.0, 2.0}));
  avg.add_window({3.0, 2.0});
  EXPECT_EQ(avg.cost(), (std::vector<double>{3.5, 3.0}));
  EXPECT_EQ(avg.windows(), 2);
}

TEST(Rebalance, BalancedOrSinglePartNeverMigrates) {
  const farm::RveGraph g = one_cell_graph();
  const std::vector<double> cost(8, 1.0);
  const std::vector<int> owner{0, 0, 0, 0, 1, 1, 1, 1};
  EXPECT_FALSE(farm::plan_rebalance(g, owner, cost, 2, 1.05, 1).migrate);
  EXPECT_FALSE(farm::plan_rebalance(g, std::vector<int>(8, 0), cost, 1, 1.0, 1).migrate);
  EXPECT_DOUBLE_EQ(farm::imbalance(owner, cost, 2), 1.0);
}

namespace {

// No decision on the first windows: they hold the start-up's noise alone.
TEST(Rebalance, AverageSettlesAfterThreeWindows) {
  farm::CostAverage avg;
  const std::vector<double> w{1.0, 1.0, 3.0};
  EXPECT_FALSE(avg.settled());
  avg.add_window(w);
  EXPECT_FALSE(avg.settled());
  avg.add_window(w);
  EXPECT_FALSE(avg.settled());
  avg.add_window(w);
  EXPECT_TRUE(avg.settled());
  EXPECT_EQ(farm::CostAverage::kSettledWindows, 3);
}

}  // namespace
