// When a coupled run writes outputs, checkpoints (keeping the newest N), balances and logs: small
// policies of the step count and the wall clock, so that the run loop only asks "due?".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "farm/run_options.hpp"

namespace farm {

/// A results.h5 row at step 0 (if the file has none), every `every` steps, and at the last step.
class OutputSchedule {
 public:
  explicit OutputSchedule(std::int64_t every) : every_(every) {}
  [[nodiscard]] bool due(std::int64_t step) const { return step % every_ == 0; }
  /// After the loop: a row for the last step unless it has one (or the file has none at all).
  [[nodiscard]] bool due_at_end(std::int64_t step, std::int64_t rows) const {
    return rows == 0 || step % every_ != 0;
  }

 private:
  std::int64_t every_;
};

/// Checkpoints every K steps and/or every T seconds of wall time, one at the end, the newest
/// `keep` kept; counts writes for fault injection.
class CheckpointSchedule {
 public:
  /// `last_step`: step of the checkpoint the run starts from (-1: none); `now`: wall clock [s].
  CheckpointSchedule(const CheckpointOptions& options, std::int64_t fault_abort_at,
                     std::int64_t last_step, double now);
  [[nodiscard]] bool due(std::int64_t step, double now) const;
  /// After the loop: at_end (or a run stopped on request) and no checkpoint of this step yet.
  [[nodiscard]] bool due_at_end(std::int64_t step, bool stopped = false) const {
    return (options_.at_end || stopped) && last_step_ != step;
  }
  /// Counts a write about to start; true if it is the one fault injection aborts.
  bool begin_write() { return ++writes_ == fault_abort_at_; }
  /// A checkpoint of `step` was written.
  void written(std::int64_t step) { last_step_ = step; }
  /// Wall-clock due-time restarts only after periodic writes (not the final one).
  void restart_clock(double now) { last_wall_ = now; }
  /// Of the checkpoints in `all` (oldest first), those beyond the newest `keep`.
  [[nodiscard]] std::vector<std::string> expired(const std::vector<std::string>& all) const;

 private:
  CheckpointOptions options_;
  std::int64_t fault_abort_at_;
  std::int64_t last_step_;
  double last_wall_;
  std::int64_t writes_ = 0;
};

/// A balance check every check_every steps, when enabled and there is more than one rank.
class BalanceSchedule {
 public:
  /// Share of the run the proposals may take (METIS dominates them; the incremental one takes
  /// 0.3-12 % of its time from 256 parts on): after a check whose proposals took m seconds with
  /// steps of s seconds, the next check waits max(check_every, m / (kMetisShare s)) steps
  /// (docs/validation/scaling.md, finding 3: 0.25 s of METIS at 10^4 RVEs on 1024 parts is 12-17 steps).
  static constexpr double kMetisShare = 0.01;
  BalanceSchedule(const BalanceOptions& options, int nranks) : options_(options), nranks_(nranks) {}
  [[nodiscard]] bool due(std::int64_t step) const {
    return options_.enabled && nranks_ > 1 && step % options_.check_every == 0 && step >= next_;
  }
  [[nodiscard]] double threshold() const { return options_.threshold; }
  /// After a check at `step` (wall clock `now` [s]) whose proposal took `metis_s` [s] (0: none
  /// made): the step time is measured since the previous check (or `start` steps and wall time
  /// given to start()); returns the steps until the next check may run (>= check_every).
  /// Timing only: which steps check never changes a result (docs/design/farm.md, "Balancing").
  std::int64_t checked(std::int64_t step, double now, double metis_s);
  /// The run's first step and wall clock [s] (the first step-time measurement starts there).
  void start(std::int64_t step, double now) {
    last_step_ = step;
    last_wall_ = now;
  }

 private:
  BalanceOptions options_;
  int nranks_;
  std::int64_t next_ = 0;       ///< no check before this step
  std::int64_t last_step_ = 0;  ///< step of the previous check (or the start)
  double last_wall_ = 0.0;      ///< its wall clock [s]
};

/// A progress line at most every `every_s` seconds of wall time.
class ProgressSchedule {
 public:
  ProgressSchedule(double every_s, double now) : every_s_(every_s), last_(now) {}
  /// True (and restarts the clock) when due: at the first call (the first step: an ETA at once,
  /// whatever the speed of the run), then every `every_s` seconds.
  bool due(double now) {
    if (!first_ && now - last_ < every_s_) return false;
    first_ = false;
    last_ = now;
    return true;
  }

 private:
  double every_s_;
  double last_;
  bool first_ = true;
};

/// The fault injection setting: MPMXDEM_FARM_FAULT=abort_checkpoint:<n> (n >= 1) if set, else
/// `configured`. Throws common::InputError on any other text.
std::int64_t fault_abort_from_env(std::int64_t configured);

/// Estimated wall time left [s]: steps left (max_steps) or time left (end_time, at the mean
/// MPM dt so far), whichever ends first, at `per_step` [s of wall per step].
double eta_s(std::int64_t step, double time, std::int64_t max_steps, double end_time,
             double per_step);

/// "1h2m3s" ("?" for a negative or non-finite duration).
std::string format_duration(double s);

}  // namespace farm
