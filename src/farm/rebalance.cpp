// Rebalancing policy (see header).
#include "farm/rebalance.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "common/errors.hpp"

namespace farm {

void CostAverage::add_window(const std::vector<double>& window) {
  if (windows_ == 0 || avg_.size() != window.size()) {
    avg_ = window;
    windows_ = 1;
    return;
  }
  for (std::size_t k = 0; k < avg_.size(); ++k) avg_[k] = decay_ * avg_[k] + window[k];
  ++windows_;
}

double imbalance(const std::vector<int>& owner, const std::vector<double>& cost, int nparts) {
  const double eff = balance_efficiency(owner, cost, nparts);
  return eff > 0.0 ? 1.0 / eff : 1.0;
}

const char* to_string(RebalanceMethod m) {
  switch (m) {
    case RebalanceMethod::incremental:
      return "incremental";
    case RebalanceMethod::metis:
      return "METIS";
    case RebalanceMethod::none:
      break;
  }
  return "none";
}

const char* fresh_name(PartitionStyle style) {
  return style == PartitionStyle::cells ? "METIS" : "spread";
}

namespace {

// Where to stop the descent: the prefix of the best net payback among those that beat the
// margin when the pay is known, else its first within kDescentSlack / 2 of where it ended.
std::size_t descent_count(const std::vector<DescentStep>& steps, const std::vector<double>& cost,
                          int nparts, double imbalance_now, double margin, const Payback& pay,
                          bool known) {
  const double mean = std::accumulate(cost.begin(), cost.end(), 0.0) / nparts;
  std::size_t count = 0;
  if (known && mean > 0.0) {
    double best_net = 0.0;
    for (std::size_t s = 0; s < steps.size(); ++s) {
      const double imb = steps[s].max_load / mean;
      if (!steps[s].ends_a_move || !(imbalance_now - imb > margin)) continue;
      const double net = pay.step_s * (1.0 - imb / imbalance_now) * pay.horizon_steps -
                         static_cast<double>(steps[s].moved) * pay.move_s_per_rve;
      if (count == 0 || net > best_net) {
        best_net = net;
        count = s + 1;
      }
    }
  }
  if (count == 0) count = descent_cut(steps, mean, kDescentSlack);
  return count;
}

// Which proposal to take: of those that beat the margin, the better net payback when the pay is
// known, else the one that moves fewer unless the other balances better by more than the margin.
RebalanceMethod choose(const RebalanceProposal& inc, const RebalanceProposal& met, double margin,
                       bool known) {
  if (inc.beats_margin && met.beats_margin) {
    bool take_metis = false;
    if (known) {
      const double net_inc = inc.saving_s - inc.move_s;
      const double net_met = met.saving_s - met.move_s;
      take_metis = net_met > net_inc || (net_met == net_inc && met.moves < inc.moves);
    } else if (met.moves < inc.moves) {
      // The one that moves fewer, unless the other balances better by more than the margin.
      take_metis = !(met.imbalance - inc.imbalance > margin);
    } else {
      take_metis = inc.imbalance - met.imbalance > margin;
    }
    return take_metis ? RebalanceMethod::metis : RebalanceMethod::incremental;
  }
  if (inc.beats_margin) return RebalanceMethod::incremental;
  if (met.beats_margin) return RebalanceMethod::metis;
  return RebalanceMethod::none;
}

}  // namespace

RebalancePlan plan_rebalance(const RveGraph& graph, const std::vector<int>& owner,
                             const std::vector<double>& cost, int nparts, double threshold,
                             int seed, const Payback& pay, PartitionStyle style) {
  MPMXDEM_CHECK(cost.size() == owner.size() && graph.size() == owner.size(),
                "one cost and one owner per RVE of the graph");
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  RebalancePlan plan;
  plan.style = style;
  plan.owner = owner;
  plan.imbalance_now = imbalance(owner, cost, nparts);
  plan.imbalance_new = plan.imbalance_now;
  if (nparts <= 1 || !(plan.imbalance_now > threshold)) return plan;
  const double margin = 0.5 * std::max(threshold - 1.0, 0.01);
  // The critical rank's time scales with the largest load; the mean does not change.
  const auto judge = [&](RebalanceProposal& p, const std::vector<int>& proposal) {
    p.imbalance = imbalance(proposal, cost, nparts);
    p.saving_s = pay.step_s * (1.0 - p.imbalance / plan.imbalance_now) * pay.horizon_steps;
    p.move_s = static_cast<double>(p.moves) * pay.move_s_per_rve;
    p.beats_margin = plan.imbalance_now - p.imbalance > margin && p.moves > 0;
  };
  const bool known = pay.step_s > 0.0 && pay.move_s_per_rve > 0.0;
  auto t0 = Clock::now();
  RveGraph no_edges;
  if (style == PartitionStyle::spread) no_edges.xadj.assign(graph.size() + 1, 0);
  const std::vector<DescentStep> steps =
      incremental_descent(style == PartitionStyle::spread ? no_edges : graph, owner, cost, nparts,
                          1.0 + 0.5 * kDescentSlack);
  const std::size_t count =
      descent_count(steps, cost, nparts, plan.imbalance_now, margin, pay, known);
  std::vector<int> incremental = apply_descent(owner, steps, count);
  plan.incremental.moves = count > 0 ? steps[count - 1].moved : 0;
  plan.incremental.time_s = seconds(t0);
  judge(plan.incremental, incremental);
  t0 = Clock::now();
  std::vector<int> metis = partition_fresh(style, graph, cost, nparts, seed);
  plan.metis.moves = keep_owners(owner, metis, nparts);
  plan.metis.time_s = seconds(t0);
  judge(plan.metis, metis);
  plan.proposal_s = plan.incremental.time_s + plan.metis.time_s;

  const RebalanceProposal& inc = plan.incremental;
  const RebalanceProposal& met = plan.metis;
  plan.method = choose(inc, met, margin, known);
  if (plan.method == RebalanceMethod::none) {
    plan.imbalance_new = std::min(inc.imbalance, met.imbalance);
    return plan;
  }
  const bool metis_chosen = plan.method == RebalanceMethod::metis;
  const RebalanceProposal& chosen = metis_chosen ? met : inc;
  plan.imbalance_new = chosen.imbalance;
  plan.moves = chosen.moves;
  plan.saving_s = chosen.saving_s;
  plan.move_s = chosen.move_s;
  if (known && !(plan.saving_s > plan.move_s)) return plan;
  plan.migrate = true;
  plan.owner = metis_chosen ? std::move(metis) : std::move(incremental);
  return plan;
}

}  // namespace farm
