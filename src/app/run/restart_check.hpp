// What a restart may continue: the checkpoint's job (dataset /job) and the new job are resolved and
// compared key by key; a changed physical key is refused, run-control keys may change
// (docs/reference/errors.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/job/job.hpp"

namespace app {

/// True for the keys a restart may change: title, mpm.end_time, output.*, farm.*.
[[nodiscard]] bool restart_may_change(const std::string& key);

/// Every key whose resolved value differs between `before` and `now` and that a restart may not
/// change, as "key = A (before) -> B (now)" (an absent key reads "(absent)"), in key order.
[[nodiscard]] std::vector<std::string> changed_physics(const Job& before, const Job& now);

/// Refuses (common::InputError) a restart of `job` from a checkpoint written with `checkpoint_job`
/// (the job text stored in it) into `out`: a job whose physics differ (each changed key named with
/// its two values), or an output directory holding another run's results (its job.toml differs
/// from the checkpoint's, or it has results.h5 but no job.toml).
void check_restart(const Job& job, const std::string& checkpoint_path,
                   const std::string& checkpoint_job, const std::filesystem::path& out);

}  // namespace app
