// `mpmxdem run JOB --out DIR --restart latest`: continue from the newest valid checkpoint of DIR,
// or start from the beginning when DIR holds none yet. One command line for every link of a chain
// of batch jobs (jobs/slurm/, docs/reference/errors.md "Restart").
#pragma once

#include <filesystem>
#include <string>

namespace app {

/// The --restart value that means "the newest valid checkpoint of --out".
inline constexpr const char* kRestartLatest = "latest";

/// The newest checkpoint_<step>.h5 of `dir` whose header and checksums verify
/// (farm::inspect_checkpoint); newer damaged ones are skipped with a warning naming them and what
/// is wrong. Returns "" when `dir` is absent or holds no checkpoint file. Throws
/// common::InputError when it holds checkpoint files and none of them verifies (each named with
/// its defect): a chain must not silently start again from the beginning over its own results.
[[nodiscard]] std::string latest_checkpoint(const std::filesystem::path& dir);

}  // namespace app
