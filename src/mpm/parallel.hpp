// OpenMP policy of the MPM module: when a loop is worth a parallel region.
#pragma once

#include <cstdint>
#include <vector>

namespace mpm {

/// Loops over fewer items than this run serially: an OpenMP fork/join per small loop costs
/// more than the work (and, on a loaded machine, far more). Results do not depend on it.
inline constexpr std::int64_t kMinParallelPoints = 4096;

/// fn(i) for i in [0, n): one `omp parallel for` (static schedule) from kMinParallelPoints items,
/// a plain loop below. Not `#pragma omp parallel for if (...)`: libgomp still starts a team of
/// one for a false if-clause, measured at 1.5-10 us per region, which was 3/4 of the MPM step of
/// the paper's 8-point job (docs/design/mpm.md, "Small problems").
template <class Fn>
inline void for_each_index(std::int64_t n, Fn&& fn) {
  if (n < kMinParallelPoints) {
    for (std::int64_t i = 0; i < n; ++i) fn(i);
    return;
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) fn(i);
}

/// out[i] = fn(i) for i in [0, n), computed as for_each_index does (out is resized to n). For
/// reductions that must give the same bits on any number of threads: the terms in parallel,
/// then the caller combines them in index order (a sum, a maximum, the first flagged index).
template <class T, class Fn>
inline void compute_terms(std::int64_t n, std::vector<T>& out, Fn&& fn) {
  out.resize(static_cast<std::size_t>(n));
  for_each_index(n, [&](std::int64_t i) { out[static_cast<std::size_t>(i)] = fn(i); });
}

}  // namespace mpm
