// Rebalancing policy (see header).
#include "farm/rebalance.hpp"

#include <algorithm>
#include <chrono>

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

RebalancePlan plan_rebalance(const RveGraph& graph, const std::vector<int>& owner,
                             const std::vector<double>& cost, int nparts, double threshold,
                             int seed, const Payback& pay) {
  MPMXDEM_CHECK(cost.size() == owner.size() && graph.size() == owner.size(),
                "one cost and one owner per RVE of the graph");
  RebalancePlan plan;
  plan.owner = owner;
  plan.imbalance_now = imbalance(owner, cost, nparts);
  plan.imbalance_new = plan.imbalance_now;
  if (nparts <= 1 || !(plan.imbalance_now > threshold)) return plan;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<int> proposal = partition_metis(graph, cost, nparts, seed);
  const auto proposal_done = [&] {
    plan.metis_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  plan.imbalance_new = imbalance(proposal, cost, nparts);
  const double margin = 0.5 * std::max(threshold - 1.0, 0.01);
  if (!(plan.imbalance_now - plan.imbalance_new > margin)) {
    proposal_done();
    return plan;
  }
  plan.moves = keep_owners(owner, proposal, nparts);
  proposal_done();
  if (plan.moves == 0) return plan;
  // The critical rank's time scales with the largest load; the mean does not change.
  plan.saving_s = pay.step_s * (1.0 - plan.imbalance_new / plan.imbalance_now) * pay.horizon_steps;
  plan.move_s = static_cast<double>(plan.moves) * pay.move_s_per_rve;
  const bool known = pay.step_s > 0.0 && pay.move_s_per_rve > 0.0;
  if (known && !(plan.saving_s > plan.move_s)) return plan;
  plan.migrate = true;
  plan.owner = std::move(proposal);
  return plan;
}

}  // namespace farm
