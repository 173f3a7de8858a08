// run_summary.json: how a run segment ended and what it did, for scripts and batch chains (the
// log's `done:` and `work:` lines as structured fields; docs/reference/outputs.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "farm/driver.hpp"

namespace app {

/// The file rank 0 writes into the output directory when a run segment ends.
inline constexpr const char* kRunSummaryFile = "run_summary.json";

/// One `mpmxdem run` (fresh or continued) as run_summary.json records it.
struct RunRecord {
  std::string job;             ///< the job file as given
  std::string restart;         ///< the checkpoint continued; "" for a fresh run
  int ranks = 1;               ///< MPI ranks
  int threads = 1;             ///< OpenMP threads per rank
  double end_time = 0.0;       ///< the job's mpm.end_time [s]
  std::int64_t max_steps = 0;  ///< --max-steps (0: none)
  int exit_code = 0;           ///< the exit status of the process
  std::string error;           ///< the numerical failure's message (exit 3), else ""
  /// The stepping loop's summary; absent when the run failed (exit 3).
  std::optional<farm::RunSummary> summary;
};

/// The farm's balance over the segment: mean over max busy time of the ranks (1 without any).
[[nodiscard]] inline double run_balance(const farm::RunSummary& s) {
  return s.times.critical_busy > 0.0 ? s.times.mean_busy / s.times.critical_busy : 1.0;
}

/// How the segment ended: "end_time", "max_steps", "max_wall", "signal" (the name in
/// `signal`), "numerical_failure".
[[nodiscard]] std::string run_end(const RunRecord& r);

/// The JSON text of run_summary.json (an object; keys in alphabetical order; finite numbers).
[[nodiscard]] std::string run_summary_json(const RunRecord& r);

/// Writes dir/run_summary.json atomically (tmp, fsync, rename). Throws common::IoError.
void write_run_summary(const std::filesystem::path& dir, const RunRecord& r);

}  // namespace app
