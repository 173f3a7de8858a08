// Grain-scale views during a coupled run (job keys [output.grains], docs/design/dem.md "Grain-scale
// views during a run"): the spheres, contacts and cell of chosen RVEs every few MPM steps, for
// ParaView, in <out>/grains/ as rve_<id>_step_<step>.vtm (+ .vtp/.vtu) and one time series
// rve_<id>.pvd per RVE. The owners of the RVEs write the views (RveFarm::write_grain_views);
// rank 0 keeps the series.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "common/param_table.hpp"
#include "dem/vtk_export.hpp"

namespace farm {

class RveFarm;

/// [output.grains]: which RVEs, how often. Empty `rves`: no views (the default). The initializer
/// of `every` is its job key's default too (kGrainViewOptions).
struct GrainViewOptions {
  std::vector<std::int64_t> rves;  ///< point ids of the RVEs drawn (ascending, each once)
  std::int64_t every = 100;        ///< MPM steps between views (>= 1); step 0 and the last too
  /// Throws common::InputError naming output.grains.rves / .every, the value and the rule, when
  /// an id is repeated or not a point of `ids` (the farm's RVE ids, ascending), or every < 1.
  void validate(const std::vector<std::int64_t>& ids) const;
};

/// [output.grains]: its numeric key (the ids, a list, are the schema's own row).
inline constexpr auto kGrainViewOptions = common::make_table<GrainViewOptions>(
    "farm::GrainViewOptions", "output.grains",
    {{"every", &GrainViewOptions::every, common::Unit::Dimensionless, common::ge(1),
      common::Source::job_default,
      "MPM steps between two views; step 0 and the last step are drawn too."}});

/// The directory of the views inside the output directory.
[[nodiscard]] std::filesystem::path grain_view_dir(const std::string& out_dir);

/// Rank 0's schedule and series of the grain views of a run.
class GrainViews {
 public:
  /// `ids`: the farm's RVE ids (ascending). `restart_step` < 0: a fresh run (the series start
  /// empty, existing ones are replaced). Otherwise the run continues a checkpoint of step
  /// `restart_step` at time `restart_time`: the series in the directory are read and their
  /// entries after `restart_time` (the abandoned continuation of that checkpoint) dropped, and
  /// the views of `restart_step` count as written. A series file that cannot be read is started
  /// anew, with a warning naming it.
  GrainViews(const GrainViewOptions& options, const std::vector<std::int64_t>& ids,
             const std::string& out_dir, std::int64_t restart_step, double restart_time);
  [[nodiscard]] bool enabled() const { return !indices_.empty(); }
  /// A view is due at MPM step `step` (every `every` steps).
  [[nodiscard]] bool due(std::int64_t step) const {
    return enabled() && step % every_ == 0 && step != last_step_;
  }
  /// After the loop: the last step unless it has its view.
  [[nodiscard]] bool due_at_end(std::int64_t step) const { return enabled() && step != last_step_; }
  /// Collective through `farm`: the views of step `step` at MPM time `time` [s], then the series
  /// files of the RVEs drawn (written by rank 0, each all or nothing). Throws common::IoError.
  void write(RveFarm& farm, std::int64_t step, double time);
  /// The series of RVE `id` as it stands (tests).
  [[nodiscard]] const std::vector<dem::VtkSeriesEntry>& series(std::int64_t id) const {
    return series_.at(id);
  }

 private:
  std::filesystem::path dir_;
  std::vector<std::size_t> indices_;  ///< RVE indices (into ids) of the chosen RVEs
  std::vector<std::int64_t> ids_;     ///< their point ids, same order
  std::int64_t every_ = 1;
  std::int64_t last_step_ = -1;  ///< step of the last views written (-1: none)
  std::map<std::int64_t, std::vector<dem::VtkSeriesEntry>> series_;  ///< by point id
};

}  // namespace farm
