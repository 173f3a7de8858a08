// Coupled driver entry points: config validation and the wrappers around CoupledRun
// (coupled_run.hpp), which builds the MPM solver on rank 0 around the RVE farm and steps it.
#include "farm/driver.hpp"

#include <algorithm>

#include "common/errors.hpp"
#include "common/param_table.hpp"
#include "farm/coupled_run.hpp"

namespace farm {

namespace {

// A CoupledConfig field that is no job key: named as the C++ member.
void bad(const std::string& member, const std::string& value, const std::string& rule) {
  throw common::InputError("farm::CoupledConfig::" + member + " = " + value + ": " + rule);
}

}  // namespace

void CoupledConfig::validate() const {
  solver.validate();
  points.validate();
  if (points.size() == 0) bad("points", "0", "a coupled run needs at least one material point");
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points.material[p] != 0) {
      bad("points.material of point id " + std::to_string(points.id[p]),
          std::to_string(points.material[p]), "must be 0 (every point is an RVE of the farm)");
    }
  }
  if (!(end_time > 0.0) && max_steps <= 0) {
    bad("end_time / max_steps", std::to_string(end_time) + " / " + std::to_string(max_steps),
        "at least one must be > 0 (when to stop)");
  }
  if (!micro.create || !micro.load)
    bad("micro", "(empty)", "a MicroKind with create and load is required");
  if (output.dir.empty()) bad("output.dir", "\"\"", "an output directory is required");
  // The options name their job keys (output.every, farm.rebalance_threshold, ...).
  common::check_ranges(kOutputOptions, output);
  common::check_ranges(kCheckpointOptions, checkpoint);
  common::check_ranges(kBalanceOptions, balance);
  std::vector<std::int64_t> ids = points.id;
  std::sort(ids.begin(), ids.end());
  grains.validate(ids);
}

RunSummary run_coupled(const CoupledConfig& config, MPI_Comm comm) {
  return CoupledRun(config, comm, nullptr).run();
}

RunSummary restart_coupled(const CoupledConfig& config, const std::string& checkpoint_path,
                           MPI_Comm comm) {
  return CoupledRun(config, comm, &checkpoint_path).run();
}

CheckpointInfo inspect_checkpoint(const std::string& path, bool verify) {
  CheckpointInfo info = read_checkpoint_info(path);
  if (verify) verify_checkpoint(path);
  return info;
}

}  // namespace farm
