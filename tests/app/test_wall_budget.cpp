// app::WallBudget: when `run --max-wall` ends a run, from the times of the calls before each step.
#include <gtest/gtest.h>

#include <chrono>

#include "app/run/wall_budget.hpp"

namespace {
app::WallBudget::Clock::time_point at(double seconds) {
  return app::WallBudget::Clock::time_point(
      std::chrono::duration_cast<app::WallBudget::Clock::duration>(
          std::chrono::duration<double>(seconds)));
}
}  // namespace

// Steps of 10 s in a budget of 100 s: the last call that lets a step start leaves 30 s; at 80 s
// the 20 s left are under 2 x 10 + 1 (a step and the checkpoint may not fit).
TEST(WallBudget, StopsWhenTwoOfTheLongestStepsAndOnePercentNoLongerFit) {
  app::WallBudget b(100.0, at(0.0));
  for (int k = 0; k <= 7; ++k) EXPECT_FALSE(b.spent(at(10.0 * k))) << "at " << 10 * k << " s";
  EXPECT_TRUE(b.spent(at(80.0)));
}

// One long step (a periodic checkpoint) counts from then on: the same time left stops a run that
// had a 30 s step and not one of 5 s steps.
TEST(WallBudget, TheLongestIntervalCounts) {
  app::WallBudget b(100.0, at(0.0));
  EXPECT_FALSE(b.spent(at(5.0)));   // before the first step
  EXPECT_FALSE(b.spent(at(10.0)));  // 90 s left, more than 2 x 5 + 1
  EXPECT_TRUE(b.spent(at(40.0)));   // a 30 s step: 60 s left, under 2 x 30 + 1
  app::WallBudget even(100.0, at(0.0));
  for (int k = 1; k <= 8; ++k) EXPECT_FALSE(even.spent(at(5.0 * k))) << "at " << 5 * k << " s";
}

// A start longer than the budget still lets the run do one step (else every link of a chain would
// end where it began); the next call stops it.
TEST(WallBudget, NeverBeforeTheFirstStep) {
  app::WallBudget b(10.0, at(0.0));
  EXPECT_FALSE(b.spent(at(30.0)));
  EXPECT_TRUE(b.spent(at(31.0)));
}
