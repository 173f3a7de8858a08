// The cut of the DEM step's loops between threads (dem/work_split.hpp): ranges that partition the
// units, a boundary that moves toward the slower thread's neighbour only when the times differ by
// more than a unit's cost, and that stays put (no oscillation) once balanced.
#include "dem/work_split.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace {

// One window of steps with the given per-step times of each thread.
void window(dem::WorkSplit& s, const std::vector<double>& per_step) {
  for (int k = 0; k < dem::WorkSplit::kWindow; ++k) {
    for (std::size_t t = 0; t < per_step.size(); ++t) s.record(static_cast<int>(t), per_step[t]);
    s.rebalance();
  }
}

TEST(WorkSplit, StartsEvenAndPartitions) {
  dem::WorkSplit s;
  s.prepare(3, 10);
  ASSERT_EQ(s.threads(), 3);
  EXPECT_EQ(s.begin(0), 0);
  EXPECT_EQ(s.end(0), s.begin(1));
  EXPECT_EQ(s.end(1), s.begin(2));
  EXPECT_EQ(s.end(2), 10);
  EXPECT_EQ(s.cut(), (std::vector<std::int64_t>{0, 3, 6, 10}));
}

// Thread 0's units cost twice thread 1's: the boundary moves one unit per window until the two
// times are within a unit's cost, then stays.
TEST(WorkSplit, MovesTowardBalanceAndStays) {
  dem::WorkSplit s;
  s.prepare(2, 30);
  std::vector<std::int64_t> cuts;
  for (int w = 0; w < 20; ++w) {
    const auto n0 = static_cast<double>(s.end(0) - s.begin(0));
    const auto n1 = static_cast<double>(s.end(1) - s.begin(1));
    window(s, {2.0 * n0, 1.0 * n1});
    cuts.push_back(s.cut()[1]);
  }
  // Balance at 2 n0 = 30 - n0: n0 = 10. A unit's mean cost (60 / 30 at the start) is the
  // threshold: it settles where |2 n0 - (30 - n0)| <= the mean cost, at 10 or 11.
  EXPECT_EQ(cuts.front(), 14);  // one unit per window
  EXPECT_GE(cuts.back(), 10);
  EXPECT_LE(cuts.back(), 11);
  // No oscillation: the last windows keep the same cut.
  EXPECT_EQ(cuts[cuts.size() - 1], cuts[cuts.size() - 5]);
}

// Times within a unit's cost do not move the cut (noise); a boundary stays inside the range.
TEST(WorkSplit, SmallDifferencesAndLimits) {
  dem::WorkSplit s;
  s.prepare(2, 8);
  window(s, {10.5, 10.0});  // a unit costs 20.5 / 8: a 0.5 difference is noise
  EXPECT_EQ(s.cut()[1], 4);
  // Moving a unit that would only swap which thread waits does not happen: one unit in all.
  dem::WorkSplit one;
  one.prepare(2, 1);
  EXPECT_EQ(one.cut(), (std::vector<std::int64_t>{0, 0, 1}));
  window(one, {0.0, 5.0});
  EXPECT_EQ(one.cut()[1], 0);
  // A thread whatever its share is slow: the boundary goes to the end of the range, not past it.
  dem::WorkSplit ends;
  ends.prepare(2, 4);
  for (int w = 0; w < 6; ++w) window(ends, {100.0, 0.0});
  EXPECT_EQ(ends.cut(), (std::vector<std::int64_t>{0, 0, 4}));
  for (int w = 0; w < 6; ++w) window(ends, {0.0, 100.0});
  EXPECT_EQ(ends.cut(), (std::vector<std::int64_t>{0, 4, 4}));
}

// Another unit count (a rebuilt pair list) keeps each boundary's fraction; another team size
// starts even again.
TEST(WorkSplit, PrepareScalesOrResets) {
  dem::WorkSplit s;
  s.prepare(2, 100);
  for (int w = 0; w < 10; ++w) window(s, {3.0, 1.0});
  const std::int64_t c = s.cut()[1];
  ASSERT_LT(c, 50);
  s.prepare(2, 200);
  EXPECT_EQ(s.cut()[1], 2 * c);
  EXPECT_EQ(s.end(1), 200);
  s.prepare(4, 200);
  EXPECT_EQ(s.cut(), (std::vector<std::int64_t>{0, 50, 100, 150, 200}));
}

}  // namespace
