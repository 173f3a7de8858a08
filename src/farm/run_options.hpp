// Options of a coupled run that are not physics: outputs, checkpoints, balancing (CoupledConfig
// in driver.hpp holds one of each). Their parameter tables (common/param_table.hpp) are the one
// home of the job keys of [output] and [farm]: the app derives the schema and the mapping from
// them, CoupledConfig::validate checks them and names those keys.
#pragma once

#include <cstdint>
#include <string>

#include "common/param_table.hpp"

namespace farm {

/// The member initializers of the numeric members are the defaults of their job keys too.
struct OutputOptions {
  std::string dir;          ///< output directory (exists, checked by the caller)
  std::int64_t every = 10;  ///< results.h5 row every N MPM steps (>= 1); step 0 and the last always
  int axial_axis = 2;       ///< axis of eps_ax in means.csv (0..2)
  double log_every_s = 10.0;  ///< progress line on rank 0 at most this often [s of wall]
};

struct CheckpointOptions {
  std::int64_t every_steps = 0;  ///< checkpoint every K MPM steps (0: off)
  double every_wall_s = 0.0;     ///< and/or every T seconds of wall time (0: off)
  std::int64_t keep = 2;         ///< newest checkpoints kept in the output dir (>= 1)
  bool at_end = true;            ///< write one after the last step
  /// Fault injection (tests): the n-th checkpoint write of this run aborts the job mid-write
  /// (MPI_Abort) leaving name.tmp behind. 0: off. The environment variable
  /// MPMXDEM_FARM_FAULT=abort_checkpoint:<n> sets it too.
  std::int64_t fault_abort_at = 0;
};

struct BalanceOptions {
  bool enabled = true;
  /// Rebalance when max/mean of the averaged rank loads exceeds this [-] (>= 1). Below 1.2, moves
  /// chase the measurement noise (docs/design/farm.md, "Balancing").
  double threshold = 1.2;
  std::int64_t check_every = 20;  ///< MPM steps between checks (>= 1)
};

using common::Source;
using common::Unit;

/// [output]: the results and progress keys (the checkpoint keys: kCheckpointOptions).
inline constexpr auto kOutputOptions = common::make_table<OutputOptions>(
    "farm::OutputOptions", "output",
    {{"every", &OutputOptions::every, Unit::Dimensionless, common::ge(1), Source::job_default,
      "Write the time series every this many MPM steps (DEM jobs: DEM steps)."},
     {"progress_interval", &OutputOptions::log_every_s, Unit::Time, common::gt(0),
      Source::job_default, "Progress line (step, strain, ETA) at most this often (wall time)."},
     {"axial_axis", &OutputOptions::axial_axis, Unit::Dimensionless, common::in_cc(0, 2),
      Source::cpp_only, "Axis of eps_ax in means.csv."}});

/// [output]: the checkpoint keys.
inline constexpr auto kCheckpointOptions = common::make_table<CheckpointOptions>(
    "farm::CheckpointOptions", "output",
    {{"checkpoint_every", &CheckpointOptions::every_steps, Unit::Dimensionless, common::ge(0),
      Source::job_default, "Write a checkpoint every this many MPM steps; 0: never."},
     {"checkpoint_interval", &CheckpointOptions::every_wall_s, Unit::Time, common::ge(0),
      Source::job_default, "Write a checkpoint every this much wall time (\"30 min\"); 0: never."},
     {"checkpoint_keep", &CheckpointOptions::keep, Unit::Dimensionless, common::ge(1),
      Source::job_default,
      "Newest checkpoints kept in the output directory (older ones are deleted)."},
     {"fault_abort_at", &CheckpointOptions::fault_abort_at, Unit::Dimensionless, common::ge(0),
      Source::cpp_only, "Fault injection: the n-th checkpoint write aborts the job; 0: off."}});

/// [farm]: the balancing keys (farm.wait: FarmOptions, wait_mode_from).
inline constexpr auto kBalanceOptions = common::make_table<BalanceOptions>(
    "farm::BalanceOptions", "farm",
    {{"rebalance_threshold", &BalanceOptions::threshold, Unit::Dimensionless, common::ge(1),
      Source::job_default,
      "Repartition the RVEs when max over mean worker busy time exceeds this."},
     {"rebalance_check_every", &BalanceOptions::check_every, Unit::Dimensionless, common::ge(1),
      Source::job_default, "MPM steps between two checks of the load balance."}});

}  // namespace farm
