// OpenMP policy of the MPM module: when a loop is worth a parallel region.
#pragma once

#include <cstdint>

namespace mpm {

/// Loops over fewer items than this run serially: an OpenMP fork/join per small loop costs
/// more than the work (and, on a loaded machine, far more). Results do not depend on it.
inline constexpr std::int64_t kMinParallelPoints = 4096;

}  // namespace mpm
