// Output directory checks and atomic writes: see output_dir.hpp.
#include "app/output_dir.hpp"

#include <fmt/format.h>

#include <fstream>

#include "common/errors.hpp"

namespace app {

namespace fs = std::filesystem;

void check_output_dir(const fs::path& dir, bool force, bool restart) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec)) {
    throw common::InputError(
        fmt::format("output directory '{}' exists and is not a directory", dir.string()));
  }
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

void write_file_atomic(const fs::path& path, const std::string& content) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw common::InputError(fmt::format("cannot write '{}'", tmp.string()));
    out << content;
    out.flush();
    if (!out) throw common::InputError(fmt::format("cannot write '{}' (disk full?)", tmp.string()));
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec)
    throw common::InputError(
        fmt::format("cannot rename '{}' to '{}': {}", tmp.string(), path.string(), ec.message()));
}

fs::path default_output_dir(const std::string& job_path) {
  return fs::path("results") / fs::path(job_path).stem();
}

}  // namespace app
