// CostLedger (see header).
#include "farm/cost_ledger.hpp"

#include <algorithm>

namespace farm {

bool CostLedger::reset(std::size_t n, const std::vector<double>* measured) {
  total_.assign(n, 0.0);
  window_.assign(n, 0.0);
  bool use = measured != nullptr && measured->size() == n;
  if (use) {
    for (double c : *measured) use = use && c > 0.0;
  }
  if (use) total_ = *measured;
  return use;
}

void CostLedger::add_step(double busy_max, double busy_mean) {
  times_.critical_busy += busy_max;
  times_.mean_busy += busy_mean;
  ++times_.steps;
}

void CostLedger::add_migration(std::int64_t moved, double wall_s, std::int64_t step) {
  if (moved > 0) ++migrations_;
  moved_ += moved;
  times_.migrate_wall += wall_s;
  step_at_migration_ = step;
}

Payback CostLedger::close_window(std::int64_t step) {
  avg_.add_window(window_);
  std::fill(window_.begin(), window_.end(), 0.0);
  Payback pay;
  const std::int64_t window_steps = times_.steps - times_at_check_.steps;
  if (window_steps > 0) {
    pay.step_s =
        (times_.critical_busy - times_at_check_.critical_busy) / static_cast<double>(window_steps);
  }
  times_at_check_ = times_;
  pay.horizon_steps = static_cast<double>(step - step_at_migration_);
  if (moved_ > 0) pay.move_s_per_rve = times_.migrate_wall / static_cast<double>(moved_);
  return pay;
}

double CostLedger::imbalance(const std::vector<int>& owner, int nranks) const {
  return farm::imbalance(owner, avg_.windows() > 0 ? avg_.cost() : window_, nranks);
}

}  // namespace farm
