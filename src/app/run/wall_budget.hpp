// `run --max-wall T`: end a run with a checkpoint before T of wall time has passed since the
// program started, for a batch job's time limit where no warning signal comes (or comes too late
// for a checkpoint: PBS's kill delay, an unset Slurm --signal), as GROMACS's -maxh does. The run
// exits 75 (EX_TEMPFAIL: to be continued) and --restart latest continues it bit for bit
// (docs/reference/errors.md, "Stopping a run").
#pragma once

#include <chrono>

namespace app {

/// The farm's stop answer (CoupledConfig::stop_requested) of a spent wall budget; signals answer
/// their number (> 0).
inline constexpr int kStopWallBudget = -1;
/// The exit code of a run stopped by its wall budget (sysexits.h EX_TEMPFAIL).
inline constexpr int kExitWallBudget = 75;

class WallBudget {
 public:
  using Clock = std::chrono::steady_clock;
  /// `seconds` of wall time from `start` (the program's start).
  WallBudget(double seconds, Clock::time_point start) : budget_(seconds), start_(start) {}
  /// Asked before every MPM step, with the time now: true when what is left may not hold one more
  /// step and the final checkpoint, that is, less than twice the longest interval between two
  /// calls so far (a step with its outputs, a periodic checkpoint included) plus 1 % of the budget.
  /// Never at the first call: a run does at least one step.
  [[nodiscard]] bool spent(Clock::time_point now);
  [[nodiscard]] double seconds() const { return budget_; }

 private:
  double budget_;
  Clock::time_point start_;
  Clock::time_point last_{};
  bool called_ = false;
  double longest_ = 0.0;  ///< [s]
};

}  // namespace app
