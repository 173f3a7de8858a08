// Offline replay of the farm's balancing (see header).
#include "farm/balance_replay.hpp"

#include <algorithm>
#include <random>

#include "common/errors.hpp"
#include "farm/cost_ledger.hpp"
#include "farm/partition.hpp"

namespace farm {

namespace {

// Each rank's busy time in one step (busy[rank]): the sum of its RVEs' costs with one thread, else
// its longest thread when each RVE goes to the thread of its rank that is free first (free_at:
// scratch, one entry per thread of each rank). Returns the step's total work.
double step_busy(const std::vector<double>& cost, const std::vector<int>& owner, int threads,
                 std::vector<std::vector<double>>& free_at, std::vector<double>& busy) {
  std::fill(busy.begin(), busy.end(), 0.0);
  double work = 0.0;
  for (std::size_t k = 0; k < cost.size(); ++k) {
    const double c = cost[k];
    work += c;
    if (threads == 1) {
      busy[static_cast<std::size_t>(owner[k])] += c;
    } else {
      std::vector<double>& th = free_at[static_cast<std::size_t>(owner[k])];
      *std::min_element(th.begin(), th.end()) += c;
    }
  }
  if (threads > 1) {
    for (std::size_t r = 0; r < busy.size(); ++r) {
      std::vector<double>& th = free_at[r];
      busy[r] = *std::max_element(th.begin(), th.end());
      std::fill(th.begin(), th.end(), 0.0);
    }
  }
  return work;
}

// The start-up, as RveFarm: blocks, then a fresh partition on the start-up weights renamed
// after them, its moves booked in the ledger (opened on n RVEs) and in res. Returns the owners.
std::vector<int> start_up(const CostTraceData& trace, const ReplayOptions& o, std::size_t n,
                          CostLedger& ledger, ReplayResult& res) {
  std::vector<int> owner = partition_blocks(n, o.parts);
  std::vector<int> part =
      partition_fresh(o.style, trace.graph, trace.start_weight, o.parts, o.seed);
  res.startup_moves = keep_owners(owner, part, o.parts);
  ledger.reset(n, nullptr);
  const std::int64_t first_step = trace.steps.front() - 1;
  ledger.set_step(first_step);
  ledger.add_migration(res.startup_moves, static_cast<double>(res.startup_moves) * o.move_s_per_rve,
                       first_step);
  return part;
}

}  // namespace

ReplayResult replay_balance(const CostTraceData& trace, const ReplayOptions& o) {
  MPMXDEM_CHECK(!trace.cpu_s.empty() && o.parts >= 1 && o.threads >= 1 && o.check_every >= 1,
                "a trace with steps, parts >= 1, threads >= 1, check_every >= 1");
  const std::size_t n = trace.cpu_s.front().size();
  const auto P = static_cast<std::size_t>(o.parts);
  ReplayResult res;
  CostLedger ledger;
  std::vector<int> owner = start_up(trace, o, n, ledger, res);
  std::mt19937_64 rng(o.jitter_seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  double sum_mean = 0.0;
  double sum_max = 0.0;
  double before[2] = {0.0, 0.0};  // mean, max before the first migration of a check
  bool migrated_once = false;
  std::vector<double> busy(P);
  std::vector<std::vector<double>> free_at(
      P, std::vector<double>(static_cast<std::size_t>(o.threads), 0.0));
  double sum_work = 0.0;
  for (std::size_t s = 0; s < trace.steps.size(); ++s) {
    const std::int64_t step = trace.steps[s];
    for (std::size_t k = 0; k < n; ++k) ledger.add_rve(k, trace.cpu_s[s][k]);
    const double work = step_busy(trace.cpu_s[s], owner, o.threads, free_at, busy);
    if (o.rank_jitter > 0.0) {
      for (double& b : busy) b *= std::max(0.0, 1.0 + o.rank_jitter * normal(rng));
    }
    double mx = 0.0;
    double sum = 0.0;
    for (const double b : busy) {
      mx = std::max(mx, b);
      sum += b;
    }
    const double mean = sum / static_cast<double>(P);
    ledger.add_step(mx, mean);
    sum_mean += mean;
    sum_max += mx;
    sum_work += work;
    if (!migrated_once) {
      before[0] += mean;
      before[1] += mx;
    }
    // The check, as Master::balance + RveFarm::rebalance_if_needed (the METIS-time stretch of
    // BalanceSchedule is left out: it never applies at these sizes).
    if (P > 1 && step % o.check_every == 0) {
      const Payback pay = ledger.close_window(step);
      if (ledger.average().windows() < o.settled_windows) continue;
      const RebalancePlan plan = plan_rebalance(trace.graph, owner, ledger.average().cost(),
                                                o.parts, o.threshold, o.seed, pay, o.style);
      ReplayCheck c;
      c.step = step;
      c.imbalance_now = plan.imbalance_now;
      c.imbalance_new = plan.imbalance_new;
      c.moves = plan.moves;
      c.migrated = plan.migrate;
      c.method = plan.method;
      res.checks.push_back(c);
      if (plan.migrate) {
        owner = plan.owner;
        res.moved += plan.moves;
        ledger.add_migration(plan.moves, static_cast<double>(plan.moves) * o.move_s_per_rve, step);
        migrated_once = true;
      }
    }
  }
  res.balance = sum_max > 0.0 ? sum_mean / sum_max : 1.0;
  res.core_efficiency =
      sum_max > 0.0 ? sum_work / (static_cast<double>(P) * o.threads * sum_max) : 1.0;
  res.balance_before_first = before[1] > 0.0 ? before[0] / before[1] : 1.0;
  const double after_max = sum_max - before[1];
  res.balance_after_first = after_max > 0.0 ? (sum_mean - before[0]) / after_max : 1.0;
  return res;
}

}  // namespace farm
