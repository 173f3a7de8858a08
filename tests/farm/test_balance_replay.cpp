// The cost trace (write, read back, refuse malformed rows) and the offline balance replay.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "farm/balance_replay.hpp"
#include "farm/cost_trace.hpp"

namespace {

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmxdem_test_balance_replay";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// A chain graph 0 - 1 - ... - (n-1).
farm::RveGraph chain(std::size_t n) {
  farm::RveGraph g;
  g.xadj.push_back(0);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) g.adjncy.push_back(static_cast<std::int64_t>(k - 1));
    if (k + 1 < n) g.adjncy.push_back(static_cast<std::int64_t>(k + 1));
    g.xadj.push_back(static_cast<std::int64_t>(g.adjncy.size()));
  }
  return g;
}

/// `steps` steps of the same costs.
farm::CostTraceData steady(const std::vector<double>& cost, int steps) {
  farm::CostTraceData d;
  d.graph = chain(cost.size());
  d.start_weight.assign(cost.size(), 1.0);
  for (int s = 1; s <= steps; ++s) {
    d.steps.push_back(s);
    d.cpu_s.push_back(cost);
    d.busy_s.push_back({0.0});
  }
  return d;
}

}  // namespace

TEST(CostTrace, WritesAndReadsBack) {
  const std::string path = temp_path("trace.csv");
  const farm::RveGraph g = chain(3);
  {
    farm::CostTrace t(path, g, {10, 11, 12}, {1.0, 2.0, 3.0});
    t.record(1, std::vector<int>{0, 0, 1}, std::vector<double>{0.5, 0.25, 0.125},
             std::vector<double>{0.75, 0.125}, std::vector<std::int64_t>{4, 2, 1},
             std::vector<std::int64_t>{0, 1, 0});
    t.record(2, std::vector<int>{0, 1, 1}, std::vector<double>{0.5, 0.5, 0.5},
             std::vector<double>{0.5, 1.0}, std::vector<std::int64_t>{4, 4, 0},
             std::vector<std::int64_t>{0, 0, 2});
  }
  const farm::CostTraceData d = farm::read_cost_trace(path);
  EXPECT_EQ(d.steps, (std::vector<std::int64_t>{1, 2}));
  ASSERT_EQ(d.cpu_s.size(), 2U);
  EXPECT_EQ(d.cpu_s[0], (std::vector<double>{0.5, 0.25, 0.125}));
  EXPECT_EQ(d.busy_s[1], (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(d.start_weight, (std::vector<double>{1.0, 2.0, 3.0}));
  ASSERT_EQ(d.dem_steps.size(), 2U);
  EXPECT_EQ(d.dem_steps[1], (std::vector<std::int64_t>{4, 4, 0}));
  ASSERT_EQ(d.rebuilds.size(), 2U);
  EXPECT_EQ(d.rebuilds[0], (std::vector<std::int64_t>{0, 1, 0}));
  EXPECT_EQ(d.rebuilds[1], (std::vector<std::int64_t>{0, 0, 2}));
  EXPECT_EQ(d.graph.xadj, g.xadj);
  EXPECT_EQ(d.graph.adjncy, g.adjncy);
}

TEST(CostTrace, ReadsATraceWrittenWithoutTheWorkColumns) {
  // Traces recorded before dem_steps and rebuilds (docs/data/balance) read back without them.
  const std::string path = temp_path("old.csv");
  { farm::CostTrace t(path, chain(2), {1, 2}, {1.0, 1.0}); }
  {
    std::ofstream out(path, std::ios::trunc);
    out << "step,rve,id,rank,cpu_s,busy_s\n1,0,1,0,0.5,0.5\n1,1,2,0,0.25,0.5\n";
  }
  const farm::CostTraceData d = farm::read_cost_trace(path);
  EXPECT_EQ(d.cpu_s[0], (std::vector<double>{0.5, 0.25}));
  EXPECT_TRUE(d.dem_steps.empty());
  EXPECT_TRUE(d.rebuilds.empty());
  {
    std::ofstream out(path, std::ios::app);
    out << "2,0,1,0,0.5,0.5,3,0\n";  // eight fields where the header has six
  }
  EXPECT_THROW((void)farm::read_cost_trace(path), common::InputError);
}

TEST(CostTrace, RefusesAMalformedRowNamingFileAndLine) {
  const std::string path = temp_path("bad.csv");
  { farm::CostTrace t(path, chain(2), {1, 2}, {1.0, 1.0}); }
  {
    std::ofstream out(path, std::ios::app);
    out << "1,0,1,0,0.5,0.5,2,0\n1,1,2,0,oops,0.5,2,0\n";
  }
  try {
    (void)farm::read_cost_trace(path);
    FAIL() << "a malformed row was read";
  } catch (const common::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path + ", line 3"), std::string::npos) << msg;
  }
}

TEST(CostTrace, CannotCreateIsAnIoErrorNamingTheFile) {
  EXPECT_THROW(farm::CostTrace("/nonexistent_dir_mpmxdem/trace.csv", chain(1), {1}, {1.0}),
               common::IoError);
}

TEST(BalanceReplay, EqualCostsStayBalancedWithoutMoves) {
  const farm::CostTraceData d = steady(std::vector<double>(8, 1e-3), 100);
  farm::ReplayOptions o;
  o.parts = 2;
  const farm::ReplayResult r = farm::replay_balance(d, o);
  EXPECT_DOUBLE_EQ(r.balance, 1.0);
  EXPECT_EQ(r.moved, 0);
  for (const auto& c : r.checks) EXPECT_FALSE(c.migrated);
}

TEST(BalanceReplay, UnknownCostsAreFixedAtTheFirstSettledCheck) {
  // The start-up sees equal weights and splits 0-3 | 4-7; the first half costs twice as much.
  std::vector<double> cost = {2e-3, 2e-3, 2e-3, 2e-3, 1e-3, 1e-3, 1e-3, 1e-3};
  const farm::CostTraceData d = steady(cost, 100);
  farm::ReplayOptions o;
  o.parts = 2;
  o.move_s_per_rve = 1e-6;
  o.style = farm::PartitionStyle::cells;  // contiguous halves of the chain: 0-3 | 4-7
  const farm::ReplayResult r = farm::replay_balance(d, o);
  // Loads 8 | 4 before: mean/max 6/8; one move makes 6 | 6.
  EXPECT_NEAR(r.balance_before_first, 6.0 / 8.0, 1e-12);
  EXPECT_NEAR(r.balance_after_first, 1.0, 1e-12);
  ASSERT_FALSE(r.checks.empty());
  EXPECT_EQ(r.checks.front().step, 20 * farm::CostAverage::kSettledWindows);
  EXPECT_TRUE(r.checks.front().migrated);
  // Settled after one window: the same move at the first check.
  o.settled_windows = 1;
  const farm::ReplayResult early = farm::replay_balance(d, o);
  EXPECT_EQ(early.checks.front().step, 20);
  EXPECT_TRUE(early.checks.front().migrated);
  EXPECT_GT(early.balance, r.balance);
}

TEST(BalanceReplay, RankJitterLowersTheBalanceAndIsReproducible) {
  const farm::CostTraceData d = steady(std::vector<double>(32, 1e-3), 50);
  farm::ReplayOptions o;
  o.parts = 4;
  o.rank_jitter = 0.1;
  const farm::ReplayResult a = farm::replay_balance(d, o);
  const farm::ReplayResult b = farm::replay_balance(d, o);
  EXPECT_EQ(a.balance, b.balance);
  EXPECT_LT(a.balance, 0.98);
  // The expected max of 4 normals is ~1.03 sigma above the mean: balance ~ 1 / 1.10.
  EXPECT_GT(a.balance, 0.85);
}

TEST(BalanceReplay, SpreadPartsAverageOutNeighboursCorrelatedCosts) {
  // 256 RVEs on a chain whose step costs rise and fall together over stretches of 16 (a smooth
  // random field along the chain, new each step), as neighbouring points' strain increments do.
  const std::size_t n = 256;
  farm::CostTraceData d;
  d.graph = chain(n);
  d.start_weight.assign(n, 1.0);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int s = 1; s <= 200; ++s) {
    std::vector<double> field(n / 16 + 2);
    for (double& f : field) f = normal(rng);
    std::vector<double> cost(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double t = static_cast<double>(k % 16) / 16.0;  // linear between the field's knots
      const double z = (1.0 - t) * field[k / 16] + t * field[k / 16 + 1];
      cost[k] = 1e-3 * std::max(0.05, 1.0 + 0.5 * z);
    }
    d.steps.push_back(s);
    d.cpu_s.push_back(cost);
    d.busy_s.push_back({0.0});
  }
  farm::ReplayOptions o;
  o.parts = 8;
  o.style = farm::PartitionStyle::cells;
  const farm::ReplayResult cells = farm::replay_balance(d, o);
  o.style = farm::PartitionStyle::spread;
  const farm::ReplayResult spread = farm::replay_balance(d, o);
  // Contiguous parts of 32 hold two stretches: their sums swing by ~0.5 / sqrt(2); spread parts
  // hold 32 RVEs from 16 stretches, sums swinging ~4x less.
  EXPECT_LT(cells.balance, 0.8);
  EXPECT_GT(spread.balance, 0.9);
  // Threads within a rank average further: 2 ranks x 4 threads beat 8 x 1 at the same cores.
  o.parts = 2;
  o.threads = 4;
  const farm::ReplayResult hybrid = farm::replay_balance(d, o);
  EXPECT_GT(hybrid.core_efficiency, spread.core_efficiency);
}
