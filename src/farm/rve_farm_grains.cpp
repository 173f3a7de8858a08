// RveFarm::write_grain_views (Command::grains): the owners of chosen RVEs write their grain-scale
// views during a run (docs/design/dem.md "Grain-scale views during a run"). Apart from rve_farm.cpp
// because it is the farm's one command that writes files from every rank.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "dem/vtk_export.hpp"
#include "farm/rve_farm.hpp"

namespace farm {

std::vector<std::size_t> RveFarm::write_grain_views(const std::vector<std::size_t>& indices,
                                                    const std::string& dir) {
  MPMXDEM_CHECK(rank_ == 0, "grain views are requested by rank 0");
  MPMXDEM_CHECK(std::is_sorted(indices.begin(), indices.end()), "indices ascending");
  for (std::size_t k : indices) MPMXDEM_CHECK(k < placement_.size(), "RVE index out of range");
  CommandHeader h;
  h.cmd = Command::grains;
  h.step = step_;
  if (size_ > 1) exchange_.send(h);
  return exec_grains(h, indices, dir);
}

std::vector<std::size_t> RveFarm::exec_grains(const CommandHeader& h,
                                              std::vector<std::size_t> indices, std::string dir) {
  if (size_ > 1) {
    auto n = static_cast<std::int64_t>(indices.size());
    MPI_Bcast(&n, 1, MPI_INT64_T, 0, comm_);
    std::vector<std::uint64_t> wire(indices.begin(), indices.end());
    wire.resize(static_cast<std::size_t>(n));
    if (n > 0) MPI_Bcast(wire.data(), to_count(wire.size()), MPI_UINT64_T, 0, comm_);
    indices.assign(wire.begin(), wire.end());
    bcast_string(comm_, dir);
  }
  // My RVEs among the chosen: their views, then one all-or-nothing write of my files. A failure
  // is reported as text (index + reason), never thrown here: every rank must reach the gather.
  std::vector<std::pair<std::size_t, std::string>> mine;  // (index, "" = drawn | "-" = no view)
  std::vector<dem::VtkFile> files;
  std::string failure;
  std::size_t failed_index = 0;
  for (std::size_t k : indices) {
    if (!models_[k]) continue;
    const std::int64_t id = placement_.ids()[k];
    try {
      std::vector<ViewFile> view = model(k).grain_view(dem::rve_view_stem(id, h.step));
      mine.emplace_back(k, view.empty() ? "-" : "");
      for (ViewFile& f : view) files.push_back({std::move(f.name), std::move(f.text)});
    } catch (const std::exception& e) {
      failure = e.what();
      failed_index = k;
      break;
    }
  }
  if (failure.empty() && !files.empty()) {
    try {
      dem::write_vtk_files(dir, files);
    } catch (const std::exception& e) {
      failure = e.what();
      failed_index = mine.empty() ? 0 : mine.front().first;
    }
  }
  if (!failure.empty()) mine = {{failed_index, "!" + failure}};
  const std::vector<std::pair<std::size_t, std::string>> all =
      size_ > 1 ? gather_texts(comm_, mine) : mine;
  if (rank_ != 0) return {};
  std::vector<std::size_t> drawn;
  for (const auto& [k, text] : all) {
    if (!text.empty() && text.front() == '!') {
      throw common::IoError(fmt::format("grain views of step {} (RVE of point id {}): {}", h.step,
                                        placement_.ids()[k], text.substr(1)));
    }
    if (text.empty()) drawn.push_back(k);
  }
  std::sort(drawn.begin(), drawn.end());
  return drawn;
}

}  // namespace farm
