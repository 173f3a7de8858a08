// farm::CoupledRun: one coupled MPM x RVE-farm run, fresh or from a checkpoint, as an object:
// construction reads the start state and builds the farm (collective); run() steps the MPM solver
// on rank 0 while the other ranks serve the farm, with output, checkpoint and balance schedules
// (run_schedules.hpp). driver.hpp's run_coupled / restart_coupled are thin wrappers.
#pragma once

#include <mpi.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/state_store.hpp"
#include "farm/driver.hpp"
#include "farm/rve_farm.hpp"

namespace farm {

class CoupledRun {
 public:
  /// Collective: validates the config, reads the checkpoint `restart` (null: a fresh run) and
  /// builds the farm. Errors are thrown on every rank alike (driver.hpp).
  CoupledRun(const CoupledConfig& config, MPI_Comm comm, const std::string* restart);
  /// Collective: steps to the end (rank 0 drives the solver, outputs, checkpoints and balancing;
  /// the other ranks serve the farm). Call once. `config` must outlive the object.
  RunSummary run();

 private:
  const CoupledConfig& cfg_;
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  std::int64_t fault_abort_at_ = 0;
  std::optional<CheckpointInfo> info_;  ///< the checkpoint restarted from
  common::StateStore mpm_state_;        ///< rank 0: its MPM state
  std::vector<std::int64_t> ids_;       ///< RVE ids, ascending
  std::unique_ptr<RveFarm> farm_;
};

}  // namespace farm
