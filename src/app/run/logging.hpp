// Rank-aware logging (spdlog): rank 0 logs at info (debug with -v, trace with -vv); other ranks
// log only warnings and errors, prefixed with their rank. Plain text unless stderr is a terminal.
#pragma once

#include <string>

namespace app {

void setup_logging(int rank, int verbosity);
/// Also log to a file (rank 0 only; other ranks ignore the call).
void add_log_file(const std::string& path);
/// Flushes and closes the log file added by add_log_file (rank 0; a no-op otherwise).
void remove_log_file() noexcept;

}  // namespace app
