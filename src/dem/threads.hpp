// When the DEM's loops over spheres and pairs run in an OpenMP region of their own, and when the
// calling thread runs them alone, without a region.
#pragma once

#include <omp.h>

#include <cstdint>

namespace dem {

/// Fewer spheres than this: one thread (a fork costs more than the work).
inline constexpr std::int64_t kParallelSpheres = 512;

/// Whether a parallel region over n spheres would run on one thread: too few spheres, one thread
/// allowed, or nested in an active region (the farm's loop over RVEs). The loops then run on the
/// calling thread without a region (work-shared constructs orphaned, or plain loops): a region of
/// one thread still costs libgomp a team (a few us and futex system calls: 25 per MPM step of a
/// 100-sphere RVE in the farm, docs/dem.md "Speed"). The same code runs either way: the same bits.
inline bool one_thread(std::int64_t n) {
  return n <= kParallelSpheres || omp_in_parallel() != 0 || omp_get_max_threads() == 1;
}

}  // namespace dem
