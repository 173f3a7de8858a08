// Offline replay of the farm's balancing on a recorded cost trace (cost_trace.hpp): the same
// CostLedger, start-up partition, check schedule and plan_rebalance as RveFarm, with P virtual
// ranks whose step time is the sum of their RVEs' recorded costs. It splits what the partition
// policy loses from what the machine adds (timing noise, rank 0's MPM share, waiting), which a real
// run mixes.
#pragma once

#include <cstdint>
#include <vector>

#include "farm/cost_trace.hpp"
#include "farm/rebalance.hpp"

namespace farm {

struct ReplayOptions {
  int parts = 2;  ///< virtual ranks owning RVEs
  /// Threads per virtual rank: its step time is the makespan of its RVEs, in ascending index
  /// order, each to the thread free first (OpenMP schedule(dynamic, 1), as RveFarm::exec_step).
  int threads = 1;
  double threshold = 1.2;         ///< farm.rebalance_threshold
  std::int64_t check_every = 20;  ///< farm.rebalance_check_every
  /// Windows the cost average needs before a decision (RveFarm: CostAverage::kSettledWindows).
  int settled_windows = CostAverage::kSettledWindows;
  double move_s_per_rve = 2e-4;  ///< a migration's cost per RVE moved [s] (measured by the farm)
  int seed = 1;                  ///< METIS_OPTION_SEED
  /// Multiplicative noise on each virtual rank's step time: normal, this coefficient of
  /// variation, clipped at 0 (0: the recorded costs as they are) [-].
  double rank_jitter = 0.0;
  std::uint64_t jitter_seed = 1;
  PartitionStyle style = PartitionStyle::spread;  ///< farm.partition
};

/// One balance check of the replay.
struct ReplayCheck {
  std::int64_t step = 0;
  double imbalance_now = 1.0;  ///< of the averaged costs under the current owners [-]
  double imbalance_new = 1.0;  ///< of the chosen proposal [-]
  std::int64_t moves = 0;
  bool migrated = false;
  RebalanceMethod method = RebalanceMethod::none;
};

struct ReplayResult {
  /// Sum over the steps of the mean virtual rank time over the sum of the largest [-]: what the
  /// farm logs as "balance (mean/max busy)".
  double balance = 1.0;
  /// Sum over the steps of the RVE time / (parts x threads) over the sum of the largest rank
  /// time: the share of the cores' time spent in RVEs [-] (= balance with one thread).
  double core_efficiency = 1.0;
  /// The balance over the steps before the first migration after the start-up, and after it [-].
  double balance_before_first = 1.0;
  double balance_after_first = 1.0;
  std::int64_t startup_moves = 0;   ///< RVEs the start-up partition moved from the blocks
  std::int64_t moved = 0;           ///< RVEs moved by the checks
  std::vector<ReplayCheck> checks;  ///< every check after the average settled
};

/// Replays `trace` (steps in order) with `options`. Deterministic for the same inputs.
/// @pre trace.cpu_s non-empty, options.parts >= 1, options.threads >= 1, options.check_every >= 1
[[nodiscard]] ReplayResult replay_balance(const CostTraceData& trace, const ReplayOptions& options);

}  // namespace farm
