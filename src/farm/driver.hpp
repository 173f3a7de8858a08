// The coupled MPM x DEM run: what `mpmxdem run job.toml` and `--restart` call. Rank 0 runs the MPM
// solver and hosts RVEs; other ranks serve the RVE farm. Entry API (small on purpose):
// CoupledConfig, run_coupled, restart_coupled, inspect_checkpoint; the run itself is
// farm/coupled_run.*. See docs/design/farm.md.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "farm/checkpoint.hpp"
#include "farm/grain_views.hpp"
#include "farm/micro_model.hpp"
#include "farm/run_options.hpp"
#include "farm/rve_farm.hpp"
#include "mpm/boundary.hpp"
#include "mpm/material_points.hpp"
#include "mpm/solver.hpp"

namespace farm {

/// Everything a coupled run needs, plain values (the app maps the job file onto it). Every rank
/// builds the same config; only rank 0 uses solver/points/constraints/tractions.
struct CoupledConfig {
  mpm::SolverConfig solver;
  mpm::MaterialPoints points;  ///< every point has material 0 and its own RVE (RVE id = point id)
  std::vector<mpm::VelocityConstraint> constraints;
  std::vector<mpm::TractionLoad> tractions;
  double end_time = 0.0;       ///< stop when the MPM time reaches this [s] (> 0)
  std::int64_t max_steps = 0;  ///< and/or after this many MPM steps in total (> 0)
  MicroKind micro;             ///< creates / restores the RVEs (ElasticMicro::kind, DemMicro::kind)
  std::string job_text;        ///< the job file, stored in checkpoints
  OutputOptions output;
  GrainViewOptions grains;  ///< grain-scale views of chosen RVEs during the run (none by default)
  CheckpointOptions checkpoint;
  BalanceOptions balance;
  FarmOptions farm;
  /// Optional, rank 0: called after every MPM step (its outputs, balancing and checkpoint
  /// included) with the step count and the farm's cumulative times; benchmarks take per-step
  /// figures from it.
  std::function<void(std::int64_t step, const FarmTimes& times)> on_step;
  /// Optional, rank 0: asked before every MPM step; a nonzero answer (the app's: the signal
  /// received, app/run/stop_signals.hpp) ends the run there as if at its end, with a checkpoint
  /// (docs/reference/errors.md, "Stopping a run").
  std::function<int()> stop_requested;
  /// Throws common::InputError naming the field, value and rule.
  void validate() const;
};

/// What a run did (complete on rank 0; steps/time on every rank).
struct RunSummary {
  std::int64_t steps = 0;                ///< MPM steps done in total (restart included)
  double time = 0.0;                     ///< MPM time reached [s]
  double wall_s = 0.0;                   ///< wall time of the stepping loop [s]
  std::vector<std::string> checkpoints;  ///< written by this run, oldest first
  FarmTimes times;                       ///< farm timing (rank 0)
  std::int64_t migrations = 0;           ///< repartitions that moved RVEs (start-up one included)
  std::int64_t rves_moved = 0;
  std::int64_t dem_steps = 0;           ///< DEM steps of all RVEs in this run's MPM steps (rank 0)
  std::int64_t rve_steps = 0;           ///< RVE steps (RVEs x MPM steps) of this run (rank 0)
  std::int64_t spared_steps = 0;        ///< of which spared (kGuardSpared: no DEM step) (rank 0)
  WaitMode wait = WaitMode::automatic;  ///< the wait mode the farm used (resolved)
  int stopped_by =
      0;  ///< stop_requested()'s nonzero answer that ended the run, else 0 (every rank)
};

/// Collective over `comm`: a fresh coupled run. Errors: common::InputError (config, exit 2),
/// common::NumericalError (an RVE or the MPM failed: RVE id, step, cause; exit 3), thrown on
/// EVERY rank with the same message (rank 0 should print it; the others stay quiet).
RunSummary run_coupled(const CoupledConfig& config, MPI_Comm comm);

/// Collective: continues the run saved in `checkpoint_path` on any number of ranks, bit for bit.
/// The config gives everything that is not state (grid, loads, end, outputs, micro kind); the
/// RVEs, points, step and time come from the checkpoint. results.h5 in config.output.dir, if
/// present, is cut back to the checkpoint's step first. A damaged or incompatible checkpoint
/// throws common::InputError naming the file and the dataset, on every rank.
RunSummary restart_coupled(const CoupledConfig& config, const std::string& checkpoint_path,
                           MPI_Comm comm);

/// Serial: reads a checkpoint's description; with `verify`, checks every dataset's checksum.
/// Throws common::InputError on a damaged or incompatible file. Print with describe(info).
CheckpointInfo inspect_checkpoint(const std::string& path, bool verify = true);

}  // namespace farm
