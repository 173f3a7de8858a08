// Output directory checks and atomic writes: see output_dir.hpp.
#include "app/output_dir.hpp"

#include <fmt/format.h>

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

fs::path default_output_dir(const std::string& job_path) {
  return fs::path("results") / fs::path(job_path).stem();
}

}  // namespace app
