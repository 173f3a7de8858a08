// Benchmarks of the MPM step: throughput (material-point updates per second) and the rank-0 cost
// per step of a scene with the issue-15 features on; callable from the app (`mpmxdem bench mpm`)
// and from the bench_mpm program. Never a test.
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

/// The scene features of issue 15 that a rank-0 MPM step pays for (docs/design/mpm.md).
struct SceneFeatures {
  bool plane_strain = true;   ///< one-cell-thick grid (y), 2 x 1 x 2 points per cell
  double mass_scaling = 100;  ///< SolverConfig::mass_scaling (1: off)
  bool gravity = true;        ///< g = 9.81 m/s^2 along -z
  /// A rigid rough base (Coulomb wall, mu = 10, on the node plane z = 0) instead of held nodes,
  /// and a gate (a smooth wall on the column's x+ side, removed at half the timed steps); the
  /// reactions of both are summed every step, as the coupled run records them.
  bool walls = true;
};

/// One measurement of the scene benchmark.
struct SceneBenchmarkResult {
  std::int64_t points = 0;  ///< material points
  std::int64_t nodes = 0;   ///< grid nodes
  int threads = 0;          ///< OpenMP threads
  std::int64_t steps = 0;   ///< timed steps (after 2 warm-up steps)
  double ms_per_step = 0.0;
  double ns_per_point_step = 0.0;
};

/// The rank-0 MPM cost per step of a scene: an elastic column under gravity (E = 1e7 Pa,
/// rho = 2000 kg/m^3, base held, a free top and sides in a padded grid) with about `num_points`
/// points and `features` on, each step followed by Solver::energies() as the coupled run's
/// quasi-static watch does. The material is LinearElastic: the DEM farm's cost is not in it.
SceneBenchmarkResult run_scene_benchmark(std::int64_t num_points, int threads, int steps,
                                         const SceneFeatures& features = {});

/// "points=... nodes=... threads=... steps=... ms/step=... ns/point-step=..." on one line.
std::string to_string(const SceneBenchmarkResult& r);

}  // namespace mpm
