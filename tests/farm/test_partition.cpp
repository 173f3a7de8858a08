// Unit tests of the METIS partition (farm/partition.hpp).
#include <gtest/gtest.h>

#include <numeric>

#include "farm/partition.hpp"

namespace {

mpm::Grid grid4() {
  return {common::Vec3::Zero(), common::Vec3(0.25, 0.25, 1.0), common::Vec3i(4, 4, 1)};
}

/// n points spread over the cells of grid4 (several per cell).
std::vector<common::Vec3> points(int n) {
  std::vector<common::Vec3> x;
  for (int k = 0; k < n; ++k) {
    x.emplace_back(0.03 + 0.94 * ((k * 7) % n) / n, 0.03 + 0.94 * ((k * 3) % n) / n, 0.5);
  }
  return x;
}

}  // namespace

TEST(Partition, CellGraphLinksPointsSharingACell) {
  const mpm::Grid g{common::Vec3::Zero(), common::Vec3(0.5, 1.0, 1.0), common::Vec3i(2, 1, 1)};
  const std::vector<common::Vec3> x{
      {0.1, 0.5, 0.5}, {0.9, 0.5, 0.5}, {0.2, 0.5, 0.5}, {0.6, 0.5, 0.5}};
  const farm::RveGraph gr = farm::cell_graph(g, x);
  ASSERT_EQ(gr.size(), 4u);
  EXPECT_EQ(gr.xadj, (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(gr.adjncy, (std::vector<std::int64_t>{2, 3, 0, 1}));
}

TEST(Partition, OnePartIsHandledWithoutMetis) {
  const auto x = points(20);
  const std::vector<double> cost(20, 1.0);
  const std::vector<int> p = farm::partition_metis(farm::cell_graph(grid4(), x), cost, 1);
  EXPECT_EQ(p, std::vector<int>(20, 0));
}

TEST(Partition, MorePartsThanRvesGivesOneEach) {
  const auto x = points(3);
  const std::vector<int> p = farm::partition_metis(farm::cell_graph(grid4(), x), {1, 1, 1}, 5);
  EXPECT_EQ(p, (std::vector<int>{0, 1, 2}));
}

TEST(Partition, WeightsAreBalanced) {
  // 64 RVEs of costs 1, 2, 3 and 10: the heavy ones must be spread.
  const int n = 64;
  const auto x = points(n);
  std::vector<double> cost(n);
  for (int k = 0; k < n; ++k) cost[static_cast<std::size_t>(k)] = k % 8 == 0 ? 10.0 : 1.0 + k % 3;
  for (int parts : {2, 3, 4}) {
    const std::vector<int> p = farm::partition_metis(farm::cell_graph(grid4(), x), cost, parts);
    for (int o : p) {
      EXPECT_GE(o, 0);
      EXPECT_LT(o, parts);
    }
    EXPECT_GE(farm::balance_efficiency(p, cost, parts), 0.95) << parts << " parts";
  }
}

TEST(Partition, Deterministic) {
  const auto x = points(50);
  std::vector<double> cost(50);
  for (int k = 0; k < 50; ++k) cost[static_cast<std::size_t>(k)] = 1.0 + (k * 13) % 7;
  const auto g = farm::cell_graph(grid4(), x);
  const auto a = farm::partition_metis(g, cost, 3, 7);
  for (int rep = 0; rep < 3; ++rep) EXPECT_EQ(farm::partition_metis(g, cost, 3, 7), a);
}

TEST(Partition, ReferenceSplits) {
  EXPECT_EQ(farm::partition_round_robin(5, 2), (std::vector<int>{0, 1, 0, 1, 0}));
  EXPECT_EQ(farm::partition_blocks(5, 2), (std::vector<int>{0, 0, 0, 1, 1}));
  EXPECT_DOUBLE_EQ(farm::balance_efficiency({0, 1}, {1.0, 3.0}, 2), 2.0 / 3.0);
}
