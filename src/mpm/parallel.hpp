// OpenMP policy of the MPM module: when a loop is worth a parallel region.
#pragma once

#include <cstdint>

namespace mpm {

/// Loops over fewer items than this run serially: an OpenMP fork/join per small loop costs
/// more than the work (and, on a loaded machine, far more). Results do not depend on it.
inline constexpr std::int64_t kMinParallelPoints = 4096;

/// fn(i) for i in [0, n): one `omp parallel for` (static schedule) from kMinParallelPoints items,
/// a plain loop below. Not `#pragma omp parallel for if (...)`: libgomp still starts a team of
/// one for a false if-clause, measured at 1.5-10 us per region, which was 3/4 of the MPM step of
/// the paper's 8-point job (docs/mpm.md, "Small problems").
template <class Fn>
inline void for_each_index(std::int64_t n, Fn&& fn) {
  if (n < kMinParallelPoints) {
    for (std::int64_t i = 0; i < n; ++i) fn(i);
    return;
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) fn(i);
}

}  // namespace mpm
