// `mpmxdem inspect CKPT [--rve ID|all ...] [--vtk DIR]`: what a checkpoint holds (checksums
// verified), the measures of chosen DEM RVEs and their grain-scale views for ParaView
// (dem/vtk_export.hpp; docs/design/dem.md "Grain-scale views"). Serial: rank 0 does everything.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "app/commands/commands.hpp"
#include "app/run/output_dir.hpp"
#include "common/errors.hpp"
#include "dem/measures.hpp"
#include "dem/state.hpp"
#include "dem/vtk_export.hpp"
#include "farm/checkpoint.hpp"
#include "farm/driver.hpp"

namespace app {

namespace {

namespace fs = std::filesystem;

/// RVEs read and written together: bounds the memory of `--rve all` on a large checkpoint.
constexpr std::size_t kBatch = 16;

/// The positions in info.ids of the RVEs that `--rve` names (ascending, each once); `all`: every
/// RVE. An id the checkpoint lacks is an InputError naming the checkpoint and its id range.
std::vector<std::int64_t> selected_rves(const farm::CheckpointInfo& info,
                                        const std::vector<std::string>& ask, bool& all) {
  all = std::find(ask.begin(), ask.end(), "all") != ask.end();
  std::set<std::int64_t> out;
  if (all) {
    for (std::size_t k = 0; k < info.ids.size(); ++k) out.insert(static_cast<std::int64_t>(k));
    return {out.begin(), out.end()};
  }
  for (const std::string& text : ask) {
    std::int64_t id = -1;
    std::from_chars(text.data(), text.data() + text.size(), id);  // checked by the CLI
    const auto it = std::lower_bound(info.ids.begin(), info.ids.end(), id);
    if (it == info.ids.end() || *it != id) {
      throw common::InputError(fmt::format(
          "checkpoint {}: --rve {}: no RVE with this point id (the checkpoint holds {} RVE(s), "
          "ids {}..{})",
          info.path, text, info.ids.size(), info.ids.empty() ? 0 : info.ids.front(),
          info.ids.empty() ? 0 : info.ids.back()));
    }
    out.insert(it - info.ids.begin());
  }
  return {out.begin(), out.end()};
}

/// The DEM RVEs among `indices`, checked (state version) before anything is written. An RVE
/// without spheres (an elastic material point) is an error when named, skipped under `all`; no
/// DEM RVE at all is an error.
std::vector<std::int64_t> dem_rves(const farm::CheckpointInfo& info,
                                   const std::vector<std::int64_t>& indices, bool all) {
  const auto states = farm::read_checkpoint_rve_states(info, indices, {"spheres/r", "dem/version"});
  std::vector<std::int64_t> out;
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const std::int64_t id = info.ids[static_cast<std::size_t>(indices[j])];
    if (!states[j].has("spheres/r")) {
      if (all) continue;
      throw common::InputError(fmt::format(
          "checkpoint {}: --rve {}: this RVE is not a DEM cell (no field spheres/r: an elastic "
          "material point?); it has no grains to measure or draw",
          info.path, id));
    }
    try {
      dem::check_state_version(states[j]);
    } catch (const common::InputError& e) {
      throw common::InputError(
          fmt::format("checkpoint {}: RVE id {}: {}", info.path, id, e.what()));
    }
    out.push_back(indices[j]);
  }
  if (out.empty()) {
    throw common::InputError(
        fmt::format("checkpoint {}: --rve all: the checkpoint holds no DEM RVE ({} RVE(s), none "
                    "with spheres: the job's materials are not DEM)",
                    info.path, info.ids.size()));
  }
  return out;
}

/// Checks (nothing written) that `dir` can receive the views, naming the checkpoint.
void check_vtk_dir(const farm::CheckpointInfo& info, const fs::path& dir) {
  try {
    check_output_dir(dir, /*force=*/true, /*restart=*/false);
  } catch (const common::InputError& e) {
    throw common::InputError(
        fmt::format("checkpoint {}: --vtk {}: {}", info.path, dir.string(), e.what()));
  }
}

std::string summary(std::int64_t id, const dem::Simulation& sim) {
  const dem::Measures m = dem::measure(sim);
  return fmt::format(
      "  RVE {:<8} {} spheres, {} contacts; p {:.6g} Pa, q {:.6g} Pa, void ratio {:.6g}, Z {:.4g}, "
      "Z without rattlers {:.4g}, unbalanced force {:.3g}, kinetic energy {:.3g} J\n",
      id, sim.spheres().size(), m.n_contacts, m.p, m.q, m.void_ratio, m.z, m.z_mech, m.unbalanced,
      m.kinetic);
}

}  // namespace

int command_inspect(const Options& o, const Comm& comm) {
  if (comm.rank != 0) return 0;
  const farm::CheckpointInfo info = farm::inspect_checkpoint(o.job, true);
  std::string out = farm::describe(info);
  if (o.rve.empty()) {
    std::fputs(out.c_str(), stdout);
    return 0;
  }
  // Everything that can be refused is refused before the first file is written.
  bool all = false;
  const std::vector<std::int64_t> asked = selected_rves(info, o.rve, all);
  const std::vector<std::int64_t> chosen = dem_rves(info, asked, all);
  const fs::path dir(o.vtk);
  std::map<std::int64_t, std::vector<dem::VtkSeriesEntry>> series;  // RVE id -> rve_<id>.pvd
  if (!o.vtk.empty()) {
    check_vtk_dir(info, dir);
    for (std::int64_t k : chosen) {
      const std::int64_t id = info.ids[static_cast<std::size_t>(k)];
      try {
        series[id] = dem::read_vtk_series_file(dir / dem::rve_series_name(id));
      } catch (const common::InputError& e) {
        throw common::InputError(fmt::format("checkpoint {}: {}", info.path, e.what()));
      }
    }
    create_output_dir(dir);
  }

  out += fmt::format("  DEM RVEs      {} of {} measured (dem::measure of the saved state){}\n",
                     chosen.size(), info.ids.size(),
                     o.vtk.empty() ? "" : "; views in " + dir.string());
  for (std::size_t b = 0; b < chosen.size(); b += kBatch) {
    const std::vector<std::int64_t> batch(
        chosen.begin() + static_cast<std::ptrdiff_t>(b),
        chosen.begin() + static_cast<std::ptrdiff_t>(std::min(chosen.size(), b + kBatch)));
    const auto states = farm::read_checkpoint_rve_states(info, batch);
    std::vector<dem::VtkFile> files;
    for (std::size_t j = 0; j < batch.size(); ++j) {
      const std::int64_t id = info.ids[static_cast<std::size_t>(batch[j])];
      try {
        const dem::Simulation sim = dem::load_simulation(states[j]);
        out += summary(id, sim);
        if (o.vtk.empty()) continue;
        const std::string stem = dem::rve_view_stem(id, info.step);
        for (dem::VtkFile& f : dem::vtk_view(sim, stem)) files.push_back(std::move(f));
        series[id] = dem::merge_vtk_series(std::move(series[id]), {info.time, stem + ".vtm"});
        files.push_back({dem::rve_series_name(id), dem::vtk_series(series[id])});
      } catch (const common::InputError& e) {
        throw common::InputError(
            fmt::format("checkpoint {}: RVE id {}: {}", info.path, id, e.what()));
      }
    }
    if (!files.empty()) dem::write_vtk_files(dir, files);
  }
  if (!o.vtk.empty()) {
    out += fmt::format(
        "  open in ParaView: {0}/rve_<id>_step_{1}.vtm (this step), {0}/rve_<id>.pvd (every step "
        "written into {0})\n",
        dir.string(), info.step);
  }
  std::fputs(out.c_str(), stdout);
  return 0;
}

}  // namespace app
