// Coupled driver entry points: config validation and the wrappers around CoupledRun
// (coupled_run.hpp), which builds the MPM solver on rank 0 around the RVE farm and steps it.
#include "farm/driver.hpp"

#include "common/errors.hpp"
#include "farm/coupled_run.hpp"

namespace farm {

namespace {

void bad(const std::string& key, const std::string& value, const std::string& rule) {
  throw common::InputError("farm config: " + key + " = " + value + ": " + rule);
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
  if (output.every < 1) bad("output.every", std::to_string(output.every), "must be >= 1 step");
  if (output.axial_axis < 0 || output.axial_axis > 2) {
    bad("output.axial_axis", std::to_string(output.axial_axis), "must be 0, 1 or 2");
  }
  if (checkpoint.every_steps < 0)
    bad("checkpoint.every_steps", std::to_string(checkpoint.every_steps), "must be >= 0");
  if (!(checkpoint.every_wall_s >= 0.0))
    bad("checkpoint.every_wall_s", std::to_string(checkpoint.every_wall_s), "must be >= 0 s");
  if (checkpoint.keep < 1) bad("checkpoint.keep", std::to_string(checkpoint.keep), "must be >= 1");
  if (!(balance.threshold >= 1.0))
    bad("balance.threshold", std::to_string(balance.threshold), "must be >= 1 (max/mean)");
  if (balance.check_every < 1)
    bad("balance.check_every", std::to_string(balance.check_every), "must be >= 1");
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
