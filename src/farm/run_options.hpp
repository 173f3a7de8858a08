// Options of a coupled run that are not physics: outputs, checkpoints, balancing (CoupledConfig
// in driver.hpp holds one of each; the app maps the job file's [output], [checkpoint] and [farm]).
#pragma once

#include <cstdint>
#include <string>

namespace farm {

struct OutputOptions {
  std::string dir;         ///< output directory (exists, checked by the caller)
  std::int64_t every = 1;  ///< results.h5 row every N MPM steps (>= 1); step 0 and the last always
  int axial_axis = 2;      ///< axis of eps_ax in means.csv (0..2)
  double log_every_s = 10.0;  ///< progress line on rank 0 at most this often [s of wall]
};

struct CheckpointOptions {
  std::int64_t every_steps = 0;  ///< checkpoint every K MPM steps (0: off)
  double every_wall_s = 0.0;     ///< and/or every T seconds of wall time (0: off)
  int keep = 2;                  ///< newest checkpoints kept in the output dir (>= 1)
  bool at_end = true;            ///< write one after the last step
  /// Fault injection (tests): the n-th checkpoint write of this run aborts the job mid-write
  /// (MPI_Abort) leaving name.tmp behind. 0: off. The environment variable
  /// MPMXDEM_FARM_FAULT=abort_checkpoint:<n> sets it too.
  std::int64_t fault_abort_at = 0;
};

struct BalanceOptions {
  bool enabled = true;
  /// Rebalance when max/mean of the averaged rank loads exceeds this [-] (>= 1). 1.2 is the job
  /// file's default: below it, moves chase the measurement noise (docs/farm.md, "Balancing").
  double threshold = 1.2;
  std::int64_t check_every = 20;  ///< MPM steps between checks (>= 1)
};

}  // namespace farm
