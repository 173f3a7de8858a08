// Throughput benchmark of the MPM step (material-point updates per second), callable from the
// app (`mpmxdem bench mpm`) and from the bench_mpm program. Never a test.
#pragma once

#include <cstdint>
#include <string>

namespace mpm {

/// One measurement.
struct BenchmarkResult {
  std::int64_t points = 0;          ///< material points in the run
  int threads = 0;                  ///< OpenMP threads used
  std::int64_t steps = 0;           ///< timed steps (after 2 warm-up steps)
  double seconds = 0.0;             ///< wall time of the timed steps [s]
  double updates_per_second = 0.0;  ///< points * steps / seconds [1/s]
  std::string shape;                ///< shape function name
};

/// Times `steps` USF steps of an elastic block under gravity (2 points per cell and direction,
/// linear elastic, bottom fixed) holding about `num_points` points, on `threads` OpenMP
/// threads (restored afterwards). shape: "linear", "ugimp" or "bspline2".
BenchmarkResult run_benchmark(std::int64_t num_points, int threads, int steps,
                              const std::string& shape = "linear");

/// "points=... threads=... steps=... seconds=... updates/s=..." on one line.
std::string to_string(const BenchmarkResult& r);

}  // namespace mpm
