// Unit tests of farm/placement.hpp: ownership lists per rank and the point slot <-> RVE index map.
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "farm/placement.hpp"

namespace {

TEST(Placement, StartsInBlocksAndListsMembersInIndexOrder) {
  const farm::Placement pl({2, 5, 7, 11, 13}, 1, 2);
  EXPECT_EQ(pl.size(), 5u);
  EXPECT_EQ(pl.nranks(), 2);
  // partition_blocks: the first ranks take the extra RVE.
  EXPECT_EQ(pl.owner(), (std::vector<int>{0, 0, 0, 1, 1}));
  EXPECT_EQ(pl.members(0), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(pl.local(), (std::vector<std::size_t>{3, 4}));
  EXPECT_EQ(pl.index_of(11), 3u);
  EXPECT_THROW((void)pl.index_of(4), common::InternalError);
}

TEST(Placement, SetOwnerRebuildsMembersAndCountsMoves) {
  farm::Placement pl({1, 2, 3, 4}, 0, 3);
  ASSERT_EQ(pl.owner(), (std::vector<int>{0, 0, 1, 2}));
  const std::vector<int> next{2, 0, 2, 1};
  EXPECT_EQ(pl.moves_to(next), 3);
  pl.set_owner(next);
  EXPECT_EQ(pl.local(), (std::vector<std::size_t>{1}));
  EXPECT_EQ(pl.members(1), (std::vector<std::size_t>{3}));
  EXPECT_EQ(pl.members(2), (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(pl.moves_to(next), 0);
  EXPECT_THROW(pl.set_owner({0, 0, 3, 0}), common::InternalError);
  EXPECT_THROW(pl.set_owner({0, 0}), common::InternalError);
}

TEST(Placement, FirstWorkerOneLeavesRankZeroWithoutRves) {
  farm::Placement pl({2, 5, 7, 11, 13}, 0, 3, 1);
  EXPECT_EQ(pl.first_worker(), 1);
  EXPECT_EQ(pl.workers(), 2);
  // Blocks over ranks 1 and 2 only; the partitioners see parts 0 and 1.
  EXPECT_EQ(pl.owner(), (std::vector<int>{1, 1, 1, 2, 2}));
  EXPECT_TRUE(pl.local().empty());
  EXPECT_EQ(pl.parts(), (std::vector<int>{0, 0, 0, 1, 1}));
  EXPECT_EQ(pl.owners_of({1, 0, 1, 0, 0}), (std::vector<int>{2, 1, 2, 1, 1}));
  pl.set_owner({2, 1, 2, 1, 1});
  EXPECT_EQ(pl.members(2), (std::vector<std::size_t>{0, 2}));
  EXPECT_THROW(pl.set_owner({0, 1, 2, 1, 1}), common::InternalError);     // rank 0 owns none
  EXPECT_THROW(farm::Placement({1, 2}, 0, 1, 1), common::InternalError);  // no worker left
}

TEST(Placement, RefusesUnsortedOrRepeatedIds) {
  EXPECT_THROW(farm::Placement({3, 1}, 0, 1), common::InternalError);
  EXPECT_THROW(farm::Placement({1, 1}, 0, 1), common::InternalError);
}

TEST(PointIndex, MapsSlotsToRveIndicesBothWays) {
  const std::vector<std::int64_t> rve_ids{10, 20, 30, 40};
  const std::vector<std::int64_t> points{30, 10, 40, 20};  // solver order
  const farm::PointIndex index(rve_ids, points);
  EXPECT_EQ(index.rve_of(0), 2u);
  EXPECT_EQ(index.rve_of(1), 0u);
  for (std::size_t p = 0; p < points.size(); ++p) EXPECT_EQ(index.slot_of(index.rve_of(p)), p);
  const std::vector<double> by_slot{3.0, 1.0, 4.0, 2.0};
  EXPECT_EQ(index.by_rve<double>(by_slot), (std::vector<double>{1.0, 2.0, 3.0, 4.0}));
  EXPECT_TRUE(index.matches(points));
  EXPECT_FALSE(index.matches(std::vector<std::int64_t>{10, 30, 40, 20}));
  EXPECT_FALSE(index.matches(std::vector<std::int64_t>{30, 10, 40}));
}

TEST(PointIndex, RefusesUnknownRepeatedOrMissingPoints) {
  const std::vector<std::int64_t> rve_ids{1, 2, 3};
  EXPECT_THROW(farm::PointIndex(rve_ids, std::vector<std::int64_t>{1, 2, 4}),
               common::InternalError);
  EXPECT_THROW(farm::PointIndex(rve_ids, std::vector<std::int64_t>{1, 2, 2}),
               common::InternalError);
  EXPECT_THROW(farm::PointIndex(rve_ids, std::vector<std::int64_t>{1, 2}), common::InternalError);
}

}  // namespace
