// Whether a coupled run's DEM RVEs fit in the memory of the nodes it runs on, checked before any
// sample is prepared or anything written: a job too large for its allocation is an input error
// naming the key that makes it large (exit 2), not std::bad_alloc or the kernel's OOM killer in
// the middle of the run (docs/reference/errors.md).
#pragma once

#include <cstdint>
#include <string>

#include "app/commands/commands.hpp"
#include "app/job/job.hpp"

namespace app {

/// Heap bytes per sphere of a DEM RVE, a lower bound: the spheres, their Verlet pairs and contacts
/// (1104 B at 4 pairs per sphere, `bench dem`'s bytes/sphere); a run's peak, with its checkpoint
/// buffers, measured about 2300 B (docs/reference/errors.md). A refusal at this figure is certain.
inline constexpr double kRveBytesPerSphere = 1024.0;

/// Memory this process may use [B]: the machine's physical memory, or its control group's limit
/// (a batch job's --mem, cgroup v2 memory.max or v1 memory.limit_in_bytes) where lower; 0 if
/// unknown.
[[nodiscard]] double usable_memory_bytes();

/// The DEM RVEs of a run, for the check below.
struct RveMemory {
  std::int64_t rves = 0;     ///< DEM RVEs of the whole run
  std::int64_t held = 0;     ///< of which this rank holds at start-up
  std::int64_t spheres = 0;  ///< spheres per RVE
  std::string key;           ///< the job key named by a refusal (what makes the run large)
};

/// Collective: the ranks sharing a node (MPI_COMM_TYPE_SHARED) add up what they hold at
/// kRveBytesPerSphere; a node whose sum exceeds its usable memory refuses the run on every rank
/// with common::InputError naming `m.key`, the figures and what to change.
void check_rve_memory(const Job& job, const RveMemory& m, const Comm& comm);

/// "1.23 GB" (decimal units, 3 significant digits).
[[nodiscard]] std::string format_bytes(double bytes);

}  // namespace app
