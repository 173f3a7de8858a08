// When the DEM's loops over spheres and pairs run in an OpenMP region of their own, and when the
// calling thread runs them alone, without a region.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>

namespace dem {

/// Fewer spheres than this: one thread (a fork costs more than the work).
inline constexpr std::int64_t kParallelSpheres = 512;

/// Spheres per thread below which a larger team loses more at its synchronisations than its
/// share of the work gains: on a 16-core Xeon, threads bound, 4 rounds (docs/design/dem.md "Speed"),
/// 1000 spheres were fastest on 8 threads (0.054-0.064 us per particle-step; 0.066-0.075 on 16),
/// 2000 on 12-16, 4000 and 8000 on 16.
inline constexpr std::int64_t kSpheresPerThread = 125;

/// Threads of a DEM region over n spheres: the OpenMP maximum, at most n / kSpheresPerThread (at
/// least 1). Which thread runs what never changes a result: only the speed.
inline int team_size(std::int64_t n) {
  const std::int64_t cap = std::max<std::int64_t>(1, n / kSpheresPerThread);
  return static_cast<int>(std::min<std::int64_t>(cap, omp_get_max_threads()));
}

/// Whether a parallel region over n spheres would run on one thread: too few spheres, one thread
/// allowed, or nested in an active region (the farm's loop over RVEs). The loops then run on the
/// calling thread without a region (work-shared constructs orphaned, or plain loops): a region of
/// one thread still costs libgomp a team (a few us and futex system calls: 25 per MPM step of a
/// 100-sphere RVE in the farm, docs/design/dem.md "Speed"). The same code runs either way: the same bits.
inline bool one_thread(std::int64_t n) {
  return n <= kParallelSpheres || omp_in_parallel() != 0 || omp_get_max_threads() == 1;
}

}  // namespace dem
