// The farm's books: measured cost of every RVE (CPU seconds of its steps), the windows and
// smoothed average that balancing decides on, the timing figures of the steps and migrations,
// and the Payback inputs of a balance check (rebalance.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "farm/rebalance.hpp"

namespace farm {

/// Per-step timing figures seen by rank 0 (cumulative since construction) [s].
struct FarmTimes {
  double step_wall = 0.0;      ///< wall time inside update_stress on rank 0
  double critical_busy = 0.0;  ///< sum over steps of the largest rank's RVE loop time
  double mean_busy = 0.0;      ///< sum over steps of the mean rank RVE loop time
  double migrate_wall = 0.0;   ///< wall time of the migrations (start-up one included)
  std::int64_t steps = 0;
};

/// Costs by RVE index (rank 0 feeds them; migration counts are kept on every rank).
class CostLedger {
 public:
  /// n RVEs with no cost measured yet; `measured` (a checkpoint's costs, may be null) becomes the
  /// total when it has n entries, all > 0. Returns whether it did.
  bool reset(std::size_t n, const std::vector<double>* measured);
  /// RVE k's step took cpu_s [s] (thread CPU time).
  void add_rve(std::size_t k, double cpu_s) {
    total_[k] += cpu_s;
    window_[k] += cpu_s;
  }
  /// One step: the ranks' RVE loop times (largest, mean) and rank 0's wall time in it [s].
  void add_step(double busy_max, double busy_mean);
  void add_step_wall(double s) { times_.step_wall += s; }
  /// A migration at MPM step `step` moved `moved` RVEs (0: a no-op) in wall_s [s].
  void add_migration(std::int64_t moved, double wall_s, std::int64_t step);
  /// The MPM step counter after a restart: the current partition dates from it.
  void set_step(std::int64_t step) { step_at_migration_ = step; }

  /// Closes the window (RVE costs since the last call) into the average and returns what a
  /// move would cost and gain: the critical rank's step time over the window, the steps since
  /// the last migration (at MPM step `step`) as horizon, the measured time per RVE moved.
  Payback close_window(std::int64_t step);
  [[nodiscard]] const CostAverage& average() const { return avg_; }
  /// Sum of the measured costs of every RVE [s] (a checkpoint's before the first step).
  [[nodiscard]] const std::vector<double>& total() const { return total_; }
  /// Max/mean over ranks of the averaged costs (of the open window before any average) [-].
  [[nodiscard]] double imbalance(const std::vector<int>& owner, int nranks) const;
  [[nodiscard]] const FarmTimes& times() const { return times_; }
  [[nodiscard]] std::int64_t migrations() const { return migrations_; }
  [[nodiscard]] std::int64_t moved() const { return moved_; }

 private:
  std::vector<double> total_;
  std::vector<double> window_;
  CostAverage avg_;
  FarmTimes times_;
  FarmTimes times_at_check_;
  std::int64_t step_at_migration_ = 0;
  std::int64_t migrations_ = 0;
  std::int64_t moved_ = 0;
};

}  // namespace farm
