// Output directory safety: a run never writes into a directory holding earlier results unless
// asked (--force) or continuing them (--restart); files are written atomically.
#pragma once

#include <filesystem>
#include <string>

#include "common/atomic_file.hpp"

namespace app {

/// Checks, without writing anything, that `dir` may receive a run's output: not "", a directory
/// (or absent) whose nearest existing ancestor is a writable directory, empty unless `force` or
/// `restart`, and not locked by a live run. Throws common::InputError naming the directory and
/// the way out when it may not.
void check_output_dir(const std::filesystem::path& dir, bool force, bool restart);
/// Creates the directory (and parents). First remembers what is there (note_output_before), so
/// that a run refused later can take back what it wrote.
void create_output_dir(const std::filesystem::path& dir);
/// Remembers the state of `dir` before a run writes into it: whether it exists (else the topmost
/// directory the run will create), its entries, the size of log.txt, and the bytes of the lock
/// file, job.toml and job.resolved.toml.
void note_output_before(const std::filesystem::path& dir);
/// Takes back what this process wrote into its output directory, for a run refused after the
/// directory was opened (an input error found late, exit 2): the directory goes when the run
/// created it (with the parents it created); otherwise the entries the run added go, log.txt is
/// cut back to its size before, and the lock file, job.toml and job.resolved.toml get their old
/// bytes back. Other files replaced in place are not restored (only --force lets a run replace
/// earlier results). Call after the log file is closed (remove_log_file). Returns what was
/// done, for the user ("" when no output directory was opened). Never throws.
std::string discard_refused_output() noexcept;
/// Takes the exclusive lock of an output directory for the rest of this process's life: the file
/// dir/mpmxdem.lock is locked (flock) and then holds "pid <pid> host <host> since <UTC time>".
/// A lock held by a live process (another run, or a stray rank of a killed launch) is an
/// InputError naming the holder; a lock file left by a process that ended is taken over. A lock
/// file that cannot be written (a full disk) is a common::IoError.
void lock_output_dir(const std::filesystem::path& dir);
/// The name of the lock file in an output directory.
inline constexpr const char* kLockFile = "mpmxdem.lock";
/// Writes a file atomically (tmp + fsync + rename): readers see the old file or the new one, never
/// a partial one. Throws common::IoError. One home: common/atomic_file.hpp.
using common::write_file_atomic;
/// Default output directory of a job: results/<job file stem>.
[[nodiscard]] std::filesystem::path default_output_dir(const std::string& job_path);

}  // namespace app
