// Unit tests of farm/cost_ledger.hpp: totals and windows by RVE, the Payback inputs of a check,
// the migration counts.
#include <gtest/gtest.h>

#include "farm/cost_ledger.hpp"

namespace {

TEST(CostLedger, UsesACheckpointsCostsOnlyWhenAllArePositive) {
  farm::CostLedger a;
  const std::vector<double> good{1.0, 2.0};
  EXPECT_TRUE(a.reset(2, &good));
  EXPECT_EQ(a.total(), good);
  const std::vector<double> zero{1.0, 0.0};
  EXPECT_FALSE(a.reset(2, &zero));
  EXPECT_EQ(a.total(), (std::vector<double>{0.0, 0.0}));
  EXPECT_FALSE(a.reset(3, &good));  // wrong size
  EXPECT_FALSE(a.reset(2, nullptr));
}

TEST(CostLedger, WindowsFeedTheAverageAndTotalsKeepEverything) {
  farm::CostLedger l;
  l.reset(2, nullptr);
  l.add_rve(0, 1.0);
  l.add_rve(1, 3.0);
  EXPECT_DOUBLE_EQ(l.imbalance({0, 1}, 2), 1.5);  // open window before any average: 3 / 2
  (void)l.close_window(10);
  EXPECT_EQ(l.average().windows(), 1);
  EXPECT_EQ(l.average().cost(), (std::vector<double>{1.0, 3.0}));
  l.add_rve(0, 2.0);
  EXPECT_EQ(l.total(), (std::vector<double>{3.0, 3.0}));
  (void)l.close_window(20);
  // avg = 0.8 * avg + window
  EXPECT_DOUBLE_EQ(l.average().cost()[0], 0.8 * 1.0 + 2.0);
  EXPECT_DOUBLE_EQ(l.average().cost()[1], 0.8 * 3.0);
}

TEST(CostLedger, PaybackFromTheWindowAndTheMigrations) {
  farm::CostLedger l;
  l.reset(4, nullptr);
  l.set_step(100);  // a restart at step 100
  l.add_step(2.0, 1.0);
  l.add_step(4.0, 1.0);
  farm::Payback p = l.close_window(110);
  EXPECT_DOUBLE_EQ(p.step_s, 3.0);          // critical rank time per step over the window
  EXPECT_DOUBLE_EQ(p.horizon_steps, 10.0);  // steps since the partition began
  EXPECT_EQ(p.move_s_per_rve, 0.0);         // nothing moved yet: not measured
  l.add_migration(4, 2.0, 110);
  l.add_migration(0, 0.5, 115);  // a no-op migration: not counted, its time is
  EXPECT_EQ(l.migrations(), 1);
  EXPECT_EQ(l.moved(), 4);
  l.add_step(1.0, 0.5);
  p = l.close_window(125);
  EXPECT_DOUBLE_EQ(p.step_s, 1.0);
  EXPECT_DOUBLE_EQ(p.horizon_steps, 10.0);
  EXPECT_DOUBLE_EQ(p.move_s_per_rve, 2.5 / 4.0);
  EXPECT_EQ(l.times().steps, 3);
  EXPECT_DOUBLE_EQ(l.times().critical_busy, 7.0);
  EXPECT_DOUBLE_EQ(l.times().migrate_wall, 2.5);
}

}  // namespace
