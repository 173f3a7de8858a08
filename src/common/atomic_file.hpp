// Atomic replacement of a file: the content goes to <path>.tmp, is fsync-ed, renamed over <path>
// and the directory is fsync-ed. Readers (and a restart after a crash or a power cut) see the old
// file or the new one, never a partial one. The one home of this protocol (checkpoints, results
// indexes, job copies, time series), and the whole-file read that goes with it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace common {

/// Where a file is staged before publish_file: `path` + ".tmp".
[[nodiscard]] std::filesystem::path staging_path(const std::filesystem::path& path);

/// Publishes a complete staged file: fsync(tmp), rename(tmp, path) (atomic on POSIX), fsync of
/// path's directory (the rename itself is then durable).
/// Throws common::IoError naming the file, the failed operation and the system's reason.
void publish_file(const std::filesystem::path& tmp, const std::filesystem::path& path);

/// Writes `content` to `path` (created or truncated) and fsyncs it; on failure removes it.
/// Throws common::IoError naming the file, the failed operation and the system's reason.
void write_new_file(const std::filesystem::path& path, std::string_view content);

/// Writes `content` to staging_path(path) and publishes it (publish_file).
/// Throws common::IoError naming the file, the failed operation and the system's reason.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// Makes sure that `bytes` more can be written next to `path` now: allocates them (fallocate, so a
/// quota counts them) in `path` + ".reserve", then removes that file. For writers that must not
/// meet a full disk half-way (HDF5, whose objects a failed write leaves half closed). Another
/// process may still take the space between this check and the write.
/// Throws common::IoError naming `path`, the size and the system's reason.
void reserve_space(const std::filesystem::path& path, std::uint64_t bytes);

/// The whole content of a file, bytes as they are ("" when it cannot be opened: callers that must
/// tell the difference check first).
[[nodiscard]] std::string read_file_bytes(const std::filesystem::path& path);

}  // namespace common
