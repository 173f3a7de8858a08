// Newest valid checkpoint of an output directory: see restart_latest.hpp.
#include "app/run/restart_latest.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <vector>

#include "common/errors.hpp"
#include "farm/checkpoint.hpp"
#include "farm/driver.hpp"

namespace app {

std::string latest_checkpoint(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return "";
  const std::vector<std::string> found = farm::list_checkpoints(dir.string());  // step ascending
  std::string defects;
  for (auto it = found.rbegin(); it != found.rend(); ++it) {
    try {
      (void)farm::inspect_checkpoint(*it, true);
      if (!defects.empty()) {
        spdlog::warn("--restart latest: newer checkpoint(s) skipped:{}", defects);
      }
      return *it;
    } catch (const std::exception& e) {  // a damaged file: the next older one may be whole
      defects += fmt::format("\n  {}: {}", *it, e.what());
    }
  }
  if (found.empty()) return "";
  throw common::InputError(fmt::format(
      "--restart latest: none of the {} checkpoint file(s) in '{}' can be read back:{}\n"
      "restart from an older copy with --restart FILE, or start again in another --out",
      found.size(), dir.string(), defects));
}

}  // namespace app
