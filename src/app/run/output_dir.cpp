// Output directory checks and atomic writes: see output_dir.hpp.
#include "app/run/output_dir.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

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

// What the output directory held before this process wrote into it (note_output_before).
struct Before {
  bool noted = false;
  fs::path dir;
  fs::path created_root;  // the topmost directory this run creates; empty when dir existed
  std::vector<std::string> entries;        // names in dir, sorted
  std::optional<std::uintmax_t> log_size;  // of log.txt, when there is one
  // The small files every run rewrites (the lock, job.toml, job.resolved.toml): name and bytes.
  std::vector<std::pair<std::string, std::string>> small;
};
constexpr const char* kRewritten[] = {kLockFile, "job.toml", "job.resolved.toml"};
Before g_before;

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

void note_output_before(const fs::path& given) {
  // "a/../b" is "b", "out/" is "out".
  fs::path dir = given.lexically_normal();
  if (dir.has_parent_path() && !dir.has_filename()) dir = dir.parent_path();
  Before b;
  b.noted = true;
  b.dir = dir;
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    b.created_root = dir;
    while (b.created_root.has_parent_path() && b.created_root.parent_path() != b.created_root &&
           !fs::exists(b.created_root.parent_path(), ec)) {
      b.created_root = b.created_root.parent_path();
    }
  } else {
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      b.entries.push_back(e.path().filename().string());
    }
    std::sort(b.entries.begin(), b.entries.end());
    if (fs::is_regular_file(dir / "log.txt", ec)) b.log_size = fs::file_size(dir / "log.txt", ec);
    for (const char* name : kRewritten) {
      if (fs::is_regular_file(dir / name, ec))
        b.small.emplace_back(name, common::read_file_bytes(dir / name));
    }
  }
  g_before = std::move(b);
}

std::string discard_refused_output() noexcept {
  try {
    if (!g_before.noted) return "";
    const Before& b = g_before;
    std::error_code ec;
    if (!b.created_root.empty()) {
      // The output directory is this run's (created and locked by it); the parents it created
      // go only if empty: another job may have started writing beside it meanwhile.
      fs::remove_all(b.dir, ec);
      if (ec) {
        return fmt::format("could not remove the output directory '{}' this run created: {}",
                           b.dir.string(), ec.message());
      }
      fs::path removed_top = b.dir;
      for (fs::path up = b.dir.parent_path(); !up.empty() && b.dir != b.created_root;
           up = up.parent_path()) {
        std::error_code rm;
        if (!fs::remove(up, rm)) break;  // not empty (or gone): it stays
        removed_top = up;
        if (up == b.created_root) break;
      }
      return fmt::format("the output directory '{}' this run created was removed",
                         removed_top.string());
    }
    std::vector<fs::path> added;  // collected first: no removal while iterating
    for (const auto& e : fs::directory_iterator(b.dir, ec)) {
      if (!std::binary_search(b.entries.begin(), b.entries.end(), e.path().filename().string())) {
        added.push_back(e.path());
      }
    }
    std::vector<std::string> removed;
    for (const fs::path& a : added) {
      std::error_code rm;
      fs::remove_all(a, rm);
      if (!rm) removed.push_back(a.filename().string());
    }
    if (b.log_size) fs::resize_file(b.dir / "log.txt", *b.log_size, ec);
    for (const auto& [name, bytes] : b.small) {
      if (common::read_file_bytes(b.dir / name) == bytes) continue;
      std::ofstream out(b.dir / name, std::ios::binary | std::ios::trunc);
      out << bytes;
    }
    std::sort(removed.begin(), removed.end());
    std::string list;
    for (const std::string& r : removed) list += (list.empty() ? "" : ", ") + r;
    return fmt::format("'{}' is as it was before this run{}", b.dir.string(),
                       removed.empty() ? std::string() : " (removed what it added: " + list + ")");
  } catch (...) {
    return "";
  }
}

void create_output_dir(const fs::path& dir) {
  note_output_before(dir);
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
    const int err = errno;
    ::close(fd);
    // The directory was writable (the file was created): the storage failed (exit 4).
    throw common::IoError(
        fmt::format("cannot write the lock file '{}': {}", file.string(), std::strerror(err)));
  }
  g_lock_fd = fd;
}

fs::path default_output_dir(const std::string& job_path) {
  return fs::path("results") / fs::path(job_path).stem();
}

}  // namespace app
