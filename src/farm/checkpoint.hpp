// Farm checkpoints: ONE parallel HDF5 file written collectively by all ranks (chunked + shuffle +
// deflate), atomic (name.tmp, fsync, rename), with a format version and a 64-bit checksum per
// dataset. Format, field names and state versions: docs/reference/checkpoint.md.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "common/state_store.hpp"

namespace farm {

inline constexpr std::int64_t kCheckpointVersion = 1;
inline constexpr const char* kCheckpointFormat = "mpmxdem-farm-checkpoint";

/// Everything a checkpoint holds besides the field data (read whole by every rank).
struct CheckpointInfo {
  std::string path;
  std::int64_t version = 0;
  std::int64_t step = 0;                ///< MPM steps done
  double time = 0.0;                    ///< MPM time [s]
  std::int64_t nranks = 0;              ///< ranks that wrote it
  std::vector<std::int64_t> ids;        ///< RVE ids, ascending
  std::vector<int> partition;           ///< owner rank of every RVE when written
  std::vector<double> cost;             ///< measured cost of every RVE [s of thread CPU time]
  std::string job_text;                 ///< the job file the run was started with
  std::vector<std::string> rve_fields;  ///< RVE state fields as listed: "f:<name>" or "i:<name>"
  std::vector<std::string> mpm_fields;  ///< MPM state fields as listed: "f:<name>" or "i:<name>"
};

/// What the collective writer needs. Vectors indexed by RVE index (ids ascending) are identical
/// on every rank; `local` holds the states of this rank's RVEs (indices ascending).
struct CheckpointData {
  std::int64_t step = 0;
  double time = 0.0;
  std::string job_text;
  std::vector<std::int64_t> ids;
  std::vector<int> owner;
  std::vector<double> cost;
  std::vector<std::int64_t> local_indices;       ///< ascending
  std::vector<common::StateStore> local_states;  ///< one per local index
  const common::StateStore* mpm = nullptr;       ///< rank 0 only (null elsewhere)
};

/// Collective: writes `final_path` atomically (final_path + ".tmp", then common::publish_file:
/// fsync, rename, fsync of the directory). A failed HDF5 write aborts the job (MPI_Abort: ranks
/// may be inside a collective); a failed publication is a common::IoError on every rank. When
/// `abort_mid_write` (fault injection), the job calls MPI_Abort after the MPM datasets and before
/// the RVE fields: the .tmp stays behind, the previous checkpoint is untouched.
void write_checkpoint(MPI_Comm comm, const std::string& final_path, const CheckpointData& data,
                      bool abort_mid_write);

/// Serial (any rank, any number of ranks): opens, checks the format, the version and the presence
/// of every dataset, verifies the checksums of the small datasets and reads them.
/// Throws common::InputError naming the file and the dataset or attribute at fault.
[[nodiscard]] CheckpointInfo read_checkpoint_info(const std::string& path);

/// Serial: reads (and verifies the checksums of) the MPM fields.
[[nodiscard]] common::StateStore read_checkpoint_mpm(const std::string& path);

/// Collective: every rank reads the states of its RVEs (indices into info.ids, ascending; each
/// RVE read by exactly one rank); the checksums of every RVE dataset are verified across ranks.
/// An error on any rank is thrown on every rank (same type and message).
[[nodiscard]] std::vector<common::StateStore> read_checkpoint_rves(
    MPI_Comm comm, const CheckpointInfo& info, const std::vector<std::int64_t>& local_indices);

/// Serial: the states of the RVEs at `indices` (positions in info.ids, any order), for
/// `mpmxdem inspect --rve`. Each RVE field is read whole, one at a time, and its checksum verified
/// (the RVEs asked for are cut out of it); only the fields named in `only` when it is not empty
/// (a cheap first look: "spheres/r"). Throws common::InputError naming the file and the dataset at
/// fault.
[[nodiscard]] std::vector<common::StateStore> read_checkpoint_rve_states(
    const CheckpointInfo& info, const std::vector<std::int64_t>& indices,
    const std::vector<std::string>& only = {});

/// Serial: reads everything and verifies every checksum (for `mpmxdem inspect`).
/// Throws common::InputError on the first problem.
void verify_checkpoint(const std::string& path);

/// Human-readable summary: format, version, step, time, RVE count, ranks that wrote it and how
/// many RVEs each held, the field lists and the job text's first line.
[[nodiscard]] std::string describe(const CheckpointInfo& info);

/// Checkpoint files `checkpoint_<step>.h5` in `dir`, oldest first.
[[nodiscard]] std::vector<std::string> list_checkpoints(const std::string& dir);
/// `dir`/checkpoint_<step, 10 digits>.h5
[[nodiscard]] std::string checkpoint_path(const std::string& dir, std::int64_t step);

}  // namespace farm
