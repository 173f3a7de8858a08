// Output directory checks and atomic writes: see output_dir.hpp.
#include "app/output_dir.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"

namespace app {

namespace fs = std::filesystem;

namespace {

std::string read_small(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string s;
  std::getline(in, s);
  return s.substr(0, 200);
}

// The holder of a live lock on dir's lock file, or "" when no live process holds it.
std::string lock_holder(const fs::path& dir) {
  const fs::path file = dir / kLockFile;
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "";
  std::string holder;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0) {
    holder = read_small(file);
    if (holder.empty()) holder = "another process";
  }
  ::close(fd);
  return holder;
}

[[noreturn]] void locked(const fs::path& dir, const std::string& holder) {
  throw common::InputError(fmt::format(
      "output directory '{}' is in use by a running mpmxdem ({}; lock file {}): wait for it to "
      "end or choose another --out",
      dir.string(), holder, (dir / kLockFile).string()));
}

int g_lock_fd = -1;  // held until the process ends

}  // namespace

void check_output_dir(const fs::path& dir, bool force, bool restart) {
  if (dir.empty()) {
    throw common::InputError("--out \"\": the output directory must not be an empty path");
  }
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    // The directory will be created: its nearest existing ancestor must be a writable directory.
    fs::path up = dir.parent_path();
    while (!up.empty() && !fs::exists(up, ec)) up = up.parent_path();
    const fs::path base = up.empty() ? fs::path(".") : up;
    if (!fs::is_directory(base, ec)) {
      throw common::InputError(
          fmt::format("cannot create output directory '{}': '{}' exists and is not a directory",
                      dir.string(), base.string()));
    }
    if (::access(base.c_str(), W_OK | X_OK) != 0) {
      throw common::InputError(fmt::format("cannot create output directory '{}': '{}': {}",
                                           dir.string(), base.string(), std::strerror(errno)));
    }
    return;
  }
  if (!fs::is_directory(dir, ec)) {
    throw common::InputError(
        fmt::format("output directory '{}' exists and is not a directory", dir.string()));
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw common::InputError(fmt::format("output directory '{}' is not writable: {}", dir.string(),
                                         std::strerror(errno)));
  }
  if (const std::string holder = lock_holder(dir); !holder.empty()) locked(dir, holder);
  if (fs::is_empty(dir, ec) || force || restart) return;
  throw common::InputError(fmt::format(
      "output directory '{}' is not empty: refusing to overwrite earlier results; choose another "
      "with "
      "--out DIR, continue a run with --restart CKPT, or pass --force to write into it anyway",
      dir.string()));
}

void create_output_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    throw common::InputError(
        fmt::format("cannot create output directory '{}': {}", dir.string(), ec.message()));
  }
}

void lock_output_dir(const fs::path& dir) {
  if (g_lock_fd >= 0) return;
  const fs::path file = dir / kLockFile;
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw common::InputError(
        fmt::format("cannot create the lock file '{}': {}", file.string(), std::strerror(errno)));
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = read_small(file);
    ::close(fd);
    locked(dir, holder.empty() ? "another process" : holder);
  }
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char when[32] = {};
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  const std::string text = fmt::format("pid {} host {} since {}\n", ::getpid(), host, when);
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) < 0) {
    ::close(fd);
    throw common::InputError(
        fmt::format("cannot write the lock file '{}': {}", file.string(), std::strerror(errno)));
  }
  g_lock_fd = fd;
}

fs::path default_output_dir(const std::string& job_path) {
  return fs::path("results") / fs::path(job_path).stem();
}

}  // namespace app
