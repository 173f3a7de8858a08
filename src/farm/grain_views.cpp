// GrainViews: the schedule and series of the grain views of a run (see header).
#include "farm/grain_views.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <system_error>

#include "common/errors.hpp"
#include "farm/rve_farm.hpp"

namespace farm {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void bad(const std::string& key, const std::string& value, const std::string& rule) {
  throw common::InputError(fmt::format("output.grains.{} = {}: {}", key, value, rule));
}

}  // namespace

void GrainViewOptions::validate(const std::vector<std::int64_t>& ids) const {
  if (rves.empty()) return;
  if (every < 1) bad("every", std::to_string(every), "must be >= 1 (MPM steps between views)");
  std::vector<std::int64_t> sorted = rves;
  std::sort(sorted.begin(), sorted.end());
  if (const auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end()) {
    bad("rves", std::to_string(*it), "listed twice (each RVE is drawn once per view step)");
  }
  for (std::int64_t id : rves) {
    if (!std::binary_search(ids.begin(), ids.end(), id)) {
      bad("rves", std::to_string(id),
          fmt::format("no material point has this id (the job's {} point(s) have ids {}..{})",
                      ids.size(), ids.empty() ? 0 : ids.front(), ids.empty() ? 0 : ids.back()));
    }
  }
}

fs::path grain_view_dir(const std::string& out_dir) { return fs::path(out_dir) / "grains"; }

GrainViews::GrainViews(const GrainViewOptions& options, const std::vector<std::int64_t>& ids,
                       const std::string& out_dir, std::int64_t restart_step, double restart_time)
    : dir_(grain_view_dir(out_dir)), every_(std::max<std::int64_t>(options.every, 1)) {
  options.validate(ids);
  std::vector<std::int64_t> chosen = options.rves;
  std::sort(chosen.begin(), chosen.end());
  for (std::int64_t id : chosen) {
    indices_.push_back(
        static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()));
    ids_.push_back(id);
    series_[id] = {};
  }
  if (restart_step < 0 || !enabled()) return;
  last_step_ = restart_step;
  for (std::int64_t id : ids_) {
    const fs::path path = dir_ / dem::rve_series_name(id);
    try {
      std::vector<dem::VtkSeriesEntry> kept;
      for (dem::VtkSeriesEntry& e : dem::read_vtk_series_file(path)) {
        if (e.time <= restart_time) kept.push_back(std::move(e));
      }
      series_[id] = std::move(kept);
    } catch (const common::InputError& e) {
      spdlog::warn("grain views: the time series {} cannot be read ({}): it starts anew",
                   path.string(), e.what());
    }
  }
}

void GrainViews::write(RveFarm& farm, std::int64_t step, double time) {
  if (!enabled()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) {
    throw common::IoError(
        fmt::format("grain views: cannot create '{}': {}", dir_.string(), ec.message()));
  }
  const std::vector<std::size_t> drawn = farm.write_grain_views(indices_, dir_.string());
  std::vector<dem::VtkFile> files;
  for (std::size_t j = 0; j < indices_.size(); ++j) {
    if (!std::binary_search(drawn.begin(), drawn.end(), indices_[j])) continue;
    const std::int64_t id = ids_[j];
    series_[id] = dem::merge_vtk_series(std::move(series_[id]),
                                        {time, dem::rve_view_stem(id, step) + ".vtm"});
    files.push_back({dem::rve_series_name(id), dem::vtk_series(series_[id])});
  }
  if (!files.empty()) dem::write_vtk_files(dir_, files);
  last_step_ = step;
}

}  // namespace farm
