// Unit tests of the rebalancing policy (farm/rebalance.hpp): no migration on timing noise, one
// migration on a real change of cost, none that does not pay back its move, and the choice between
// the incremental and the METIS proposal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

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

namespace {

/// 3 of 4 identical RVEs on part 0: imbalance 1.5, METIS balances them by moving one.
struct Lopsided {
  farm::RveGraph g = farm::RveGraph{{0, 0, 0, 0, 0}, {}};
  std::vector<int> owner{0, 0, 0, 1};
  std::vector<double> cost = std::vector<double>(4, 1.0);
};

}  // namespace

// Saving = 1 ms per step x (1 - 1/1.5) x 100 steps = 33 ms: a move of 10 ms per RVE pays, one of
// 100 ms does not; an unmeasured move (0) is free, as before payback existed.
TEST(Rebalance, AMoveMustPayBackWithinTheHorizon) {
  const Lopsided l;
  farm::Payback pay{1e-3, 100.0, 0.1};
  const farm::RebalancePlan no = farm::plan_rebalance(l.g, l.owner, l.cost, 2, 1.2, 1, pay);
  EXPECT_FALSE(no.migrate);
  EXPECT_EQ(no.owner, l.owner);
  EXPECT_EQ(no.moves, 1);  // the renamed proposal moves one RVE of part 0
  EXPECT_NEAR(no.saving_s, 1e-3 / 3.0 * 100.0, 1e-12);
  EXPECT_NEAR(no.move_s, 0.1, 1e-12);
  pay.move_s_per_rve = 0.01;
  const farm::RebalancePlan yes = farm::plan_rebalance(l.g, l.owner, l.cost, 2, 1.2, 1, pay);
  EXPECT_TRUE(yes.migrate);
  EXPECT_DOUBLE_EQ(farm::imbalance(yes.owner, l.cost, 2), 1.0);
  pay.move_s_per_rve = 0.0;
  EXPECT_TRUE(farm::plan_rebalance(l.g, l.owner, l.cost, 2, 1.2, 1, pay).migrate);
  EXPECT_TRUE(farm::plan_rebalance(l.g, l.owner, l.cost, 2, 1.2, 1).migrate);
}

// METIS names parts arbitrarily: the renaming keeps every RVE it can where it is.
TEST(Rebalance, KeepOwnersRenamesPartsToMoveLeast) {
  const std::vector<int> current{0, 0, 0, 0, 1, 1, 1, 1};
  std::vector<int> swapped{1, 1, 1, 1, 0, 0, 0, 0};
  EXPECT_EQ(farm::keep_owners(current, swapped, 2), 0);
  EXPECT_EQ(swapped, current);
  std::vector<int> one_moves{1, 1, 1, 0, 0, 0, 0, 0};  // RVE 3 changes side, named the other way
  EXPECT_EQ(farm::keep_owners(current, one_moves, 2), 1);
  EXPECT_EQ(one_moves, (std::vector<int>{0, 0, 0, 1, 1, 1, 1, 1}));
  const std::vector<int> three{0, 0, 1, 1, 2, 2};
  std::vector<int> rotated{2, 2, 0, 0, 1, 1};
  EXPECT_EQ(farm::keep_owners(three, rotated, 3), 0);
  EXPECT_EQ(rotated, three);
}

namespace {
// The renaming as first written: the dense P x P table scanned P times (O(P^3)), the reference
// the O(N log N) version must equal exactly (same greedy order and ties).
std::vector<int> keep_owners_dense(const std::vector<int>& current, std::vector<int> proposal,
                                   int nparts) {
  const auto np = static_cast<std::size_t>(nparts);
  std::vector<std::int64_t> shared(np * np, 0);
  for (std::size_t k = 0; k < current.size(); ++k)
    ++shared[static_cast<std::size_t>(proposal[k]) * np + static_cast<std::size_t>(current[k])];
  std::vector<int> rename(np, -1);
  std::vector<bool> taken(np, false);
  for (std::size_t round = 0; round < np; ++round) {
    std::int64_t best = -1;
    std::size_t bn = 0;
    std::size_t bo = 0;
    for (std::size_t n = 0; n < np; ++n) {
      if (rename[n] >= 0) continue;
      for (std::size_t o = 0; o < np; ++o) {
        if (!taken[o] && shared[n * np + o] > best) {
          best = shared[n * np + o];
          bn = n;
          bo = o;
        }
      }
    }
    rename[bn] = static_cast<int>(bo);
    taken[bo] = true;
  }
  for (int& p : proposal) p = rename[static_cast<std::size_t>(p)];
  return proposal;
}
}  // namespace

// Random ownerships, some parts empty, many ties: the same renaming as the dense scan.
TEST(Rebalance, KeepOwnersEqualsTheDenseGreedyScan) {
  std::mt19937 gen(7);
  for (int trial = 0; trial < 300; ++trial) {
    const int parts = 1 + static_cast<int>(gen() % 40);
    const std::size_t rves = gen() % 200;
    std::vector<int> current(rves);
    std::vector<int> proposal(rves);
    const int used = 1 + static_cast<int>(gen() % static_cast<unsigned>(parts));  // some empty
    for (std::size_t k = 0; k < rves; ++k) {
      current[k] = static_cast<int>(gen() % static_cast<unsigned>(used));
      proposal[k] = static_cast<int>(gen() % static_cast<unsigned>(parts));
    }
    const std::vector<int> expected = keep_owners_dense(current, proposal, parts);
    std::int64_t moves = 0;
    for (std::size_t k = 0; k < rves; ++k) moves += expected[k] != current[k] ? 1 : 0;
    std::vector<int> got = proposal;
    ASSERT_EQ(farm::keep_owners(current, got, parts), moves) << "trial " << trial;
    ASSERT_EQ(got, expected) << "trial " << trial;
  }
}

namespace {

/// 1000 RVEs on a 10^3 lattice (8 per grid cell), costs uniform in [1, 2], balanced over 32 parts
/// by METIS; then part 0's RVEs become 10 % dearer.
struct Perturbed {
  farm::RveGraph g;
  std::vector<double> cost;
  std::vector<int> owner;
  Perturbed() {
    const mpm::Grid grid{common::Vec3::Zero(), common::Vec3::Constant(0.2), common::Vec3i(5, 5, 5)};
    std::vector<common::Vec3> x;
    for (int k = 0; k < 1000; ++k)
      x.emplace_back((k % 10 + 0.5) / 10, ((k / 10) % 10 + 0.5) / 10, (k / 100 + 0.5) / 10);
    g = farm::cell_graph(grid, x);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(1.0, 2.0);
    for (int k = 0; k < 1000; ++k) cost.push_back(u(gen));
    owner = farm::partition_metis(g, cost, 32);
    for (std::size_t k = 0; k < cost.size(); ++k) cost[k] *= owner[k] == 0 ? 1.1 : 1.0;
  }
};

/// Two parts: {3, 3, 0.4, 0.4, 0.4} and {2, 2} (imbalance 7.2 / 5.6 = 1.286). The incremental
/// descent moves the three 0.4 and is then stuck at 6 / 5.6 = 1.071 (no single RVE fits); METIS
/// also swaps a 3 and a 2: 5.8 / 5.6 = 1.036, with at least as many moves.
struct Stuck {
  farm::RveGraph g = farm::RveGraph{std::vector<std::int64_t>(8, 0), {}};
  std::vector<int> owner{0, 0, 0, 0, 0, 1, 1};
  std::vector<double> cost{3.0, 3.0, 0.4, 0.4, 0.4, 2.0, 2.0};
};

}  // namespace

// A small perturbation of a balanced partition: both proposals beat the margin, the incremental
// one moves far fewer RVEs to about the same imbalance, and is chosen (payback unknown or known).
TEST(Rebalance, SmallPerturbationIsFixedIncrementally) {
  const Perturbed p;
  const farm::RebalancePlan plan = farm::plan_rebalance(p.g, p.owner, p.cost, 32, 1.05, 1);
  EXPECT_GT(plan.imbalance_now, 1.08);
  EXPECT_TRUE(plan.incremental.beats_margin);
  EXPECT_TRUE(plan.metis.beats_margin);
  EXPECT_LT(10 * plan.incremental.moves, plan.metis.moves);
  EXPECT_TRUE(plan.migrate);
  EXPECT_EQ(plan.method, farm::RebalanceMethod::incremental);
  EXPECT_STREQ(farm::to_string(plan.method), "incremental");
  EXPECT_EQ(plan.moves, plan.incremental.moves);
  EXPECT_DOUBLE_EQ(plan.imbalance_new, plan.incremental.imbalance);
  EXPECT_DOUBLE_EQ(farm::imbalance(plan.owner, p.cost, 32), plan.imbalance_new);
  EXPECT_LT(plan.imbalance_new, 1.025);
  EXPECT_GT(plan.proposal_s, 0.0);
  // Payback known, 1 ms per step over 1000 steps, 1 ms per moved RVE: the incremental proposal
  // nets more (it saves about as much and moves a fraction).
  const farm::Payback pay{1e-3, 1000.0, 1e-3};
  const farm::RebalancePlan paid = farm::plan_rebalance(p.g, p.owner, p.cost, 32, 1.05, 1, pay);
  EXPECT_EQ(paid.method, farm::RebalanceMethod::incremental);
  EXPECT_TRUE(paid.migrate);
  const double net = paid.incremental.saving_s - paid.incremental.move_s;
  EXPECT_GT(net, paid.metis.saving_s - paid.metis.move_s);
  // The descent is stopped where its net is best: at least the net of the slack rule's stop.
  const double slack_net =
      pay.step_s * (1.0 - plan.incremental.imbalance / plan.imbalance_now) * pay.horizon_steps -
      static_cast<double>(plan.incremental.moves) * pay.move_s_per_rve;
  EXPECT_GE(net, slack_net - 1e-9);
  EXPECT_DOUBLE_EQ(farm::imbalance(paid.owner, p.cost, 32), paid.imbalance_new);
}

// Where the incremental descent is stuck well above what METIS reaches, METIS is chosen: by the
// imbalance rule when payback is unknown, by the net saving when it is known.
TEST(Rebalance, MetisIsChosenWhereTheIncrementalProposalIsStuck) {
  const Stuck s;
  const farm::RebalancePlan plan = farm::plan_rebalance(s.g, s.owner, s.cost, 2, 1.05, 1);
  EXPECT_NEAR(plan.imbalance_now, 7.2 / 5.6, 1e-12);
  EXPECT_NEAR(plan.incremental.imbalance, 6.0 / 5.6, 1e-12);
  EXPECT_EQ(plan.incremental.moves, 3);
  EXPECT_TRUE(plan.incremental.beats_margin);
  EXPECT_NEAR(plan.metis.imbalance, 5.8 / 5.6, 1e-12);
  EXPECT_GE(plan.metis.moves, plan.incremental.moves);
  EXPECT_EQ(plan.method, farm::RebalanceMethod::metis);
  EXPECT_TRUE(plan.migrate);
  EXPECT_NEAR(farm::imbalance(plan.owner, s.cost, 2), 5.8 / 5.6, 1e-12);
  // Payback known: METIS saves 0.1 s x (1 - 1.036 / 1.286) = 19.4 ms, the incremental proposal
  // 16.7 ms, for the same 3 ms of moves.
  const farm::Payback pay{1e-3, 100.0, 1e-3};
  const farm::RebalancePlan paid = farm::plan_rebalance(s.g, s.owner, s.cost, 2, 1.05, 1, pay);
  EXPECT_EQ(paid.method, farm::RebalanceMethod::metis);
  EXPECT_TRUE(paid.migrate);
  // At a threshold of 1.1 (margin 0.05) METIS's advantage (0.036) is noise: the incremental
  // proposal, which moves no more RVEs, is chosen.
  const farm::RebalancePlan loose = farm::plan_rebalance(s.g, s.owner, s.cost, 2, 1.1, 1);
  EXPECT_EQ(loose.method, farm::RebalanceMethod::incremental);
  EXPECT_TRUE(loose.migrate);
  EXPECT_EQ(loose.moves, 3);
}

// Below the threshold nothing is proposed; a gain inside the margin is not adopted.
TEST(Rebalance, NoProposalIsMadeOrChosenWithoutAGain) {
  const Perturbed p;
  const farm::RebalancePlan calm = farm::plan_rebalance(p.g, p.owner, p.cost, 32, 1.2, 1);
  EXPECT_FALSE(calm.migrate);
  EXPECT_EQ(calm.method, farm::RebalanceMethod::none);
  EXPECT_EQ(calm.proposal_s, 0.0);
  EXPECT_STREQ(farm::to_string(calm.method), "none");
}
