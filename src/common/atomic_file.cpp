// Atomic file replacement: see atomic_file.hpp.
#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.hpp"

namespace common {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const char* what, int err) {
  throw IoError("cannot " + std::string(what) + " '" + path.string() + "': " + std::strerror(err));
}

/// Closes a file descriptor on scope exit.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  [[nodiscard]] int get() const { return fd_; }
  /// Closes now and reports the result (a deferred write error can surface here).
  int close() {
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc;
  }

 private:
  int fd_;
};

void fsync_path(const fs::path& path, bool directory) {
  Fd fd(::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY));
  if (fd.get() < 0) fail(path, "open for fsync", errno);
  if (::fsync(fd.get()) != 0) fail(path, "fsync", errno);
}

/// rename(tmp, path), then fsync of the directory so that the rename survives a power cut.
void rename_durably(const fs::path& tmp, const fs::path& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    throw IoError("cannot rename '" + tmp.string() + "' to '" + path.string() +
                  "': " + std::strerror(errno));
  }
  const fs::path dir = path.parent_path();
  fsync_path(dir.empty() ? fs::path(".") : dir, true);
}

/// Writes all of `content` to a new `tmp` and fsyncs it.
void write_synced(const fs::path& tmp, std::string_view content) {
  Fd fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) fail(tmp, "create", errno);
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd.get(), content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(tmp, "write", errno);
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd.get()) != 0) fail(tmp, "fsync", errno);
  if (fd.close() != 0) fail(tmp, "close", errno);
}

}  // namespace

fs::path staging_path(const fs::path& path) { return fs::path(path.string() + ".tmp"); }

void publish_file(const fs::path& tmp, const fs::path& path) {
  fsync_path(tmp, false);
  rename_durably(tmp, path);
}

void write_new_file(const fs::path& path, std::string_view content) {
  try {
    write_synced(path, content);
  } catch (const IoError&) {
    ::unlink(path.c_str());  // best effort: do not leave a partial file filling the disk
    throw;
  }
}

void write_file_atomic(const fs::path& path, std::string_view content) {
  const fs::path tmp = staging_path(path);
  write_new_file(tmp, content);
  rename_durably(tmp, path);
}

void reserve_space(const fs::path& path, std::uint64_t bytes) {
  const fs::path probe(path.string() + ".reserve");
  Fd fd(::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) fail(probe, "create", errno);
  const int err = ::posix_fallocate(fd.get(), 0, static_cast<off_t>(bytes));
  fd.close();
  ::unlink(probe.c_str());
  if (err != 0) {
    throw IoError("no room for the next " + std::to_string(bytes) + " bytes of '" + path.string() +
                  "': " + std::strerror(err));
  }
}

std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace common
