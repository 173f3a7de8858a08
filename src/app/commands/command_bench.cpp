// `mpmxdem bench dem|mpm`: performance figures on 1 and 2 threads (and more if available).
// Benchmarks print figures; they are never tests.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands/commands.hpp"
#include "dem/benchmark.hpp"
#include "dem/packing_io.hpp"
#include "dem/reference_material.hpp"
#include "mpm/benchmark.hpp"
#include "mpm/shape_function.hpp"

namespace app {

namespace {

// DEM: drained triaxial shearing of the reference packing tiled n x n x n (n^3 x 1000 spheres),
// on 1, 2, 4, ... threads; the speed-up is against the 1-thread run of the same size.
int bench_dem(const Options& o, int max_threads) {
  const std::string path = dem::reference_packing_path();
  const dem::Packing base = dem::read_packing(path);
  const std::vector<int> tiles = o.bench_size > 0 ? std::vector<int>{static_cast<int>(o.bench_size)}
                                                  : std::vector<int>{1, 2, 3};
  dem::BenchmarkConfig cfg;
  std::printf(
      "# dem: us per particle-step of drained triaxial shearing at I = %g, reference material, "
      "%g kPa confining, packing %s tiled n x n x n, min(500, steps) untimed warm-up steps "
      "first, hash = bits of the final state (equal for every thread count)\n",
      cfg.inertial_number, cfg.confining / 1e3, path.c_str());
  for (const int n : tiles) {
    const auto spheres = static_cast<std::int64_t>(base.r.size()) * n * n * n;
    // About 3e6 particle-steps per run (0.5-1 s on one thread) unless --steps says otherwise.
    cfg.tiles = n;
    cfg.steps = o.bench_steps > 0
                    ? o.bench_steps
                    : std::max<std::int64_t>(100, 3'000'000 / std::max<std::int64_t>(spheres, 1));
    cfg.warmup_steps = std::min<std::int64_t>(500, cfg.steps);
    double one = 0.0;
    for (int t = 1; t <= std::max(2, max_threads); t *= 2) {
      cfg.threads = t;
      const dem::BenchmarkResult r =
          dem::run_benchmark(base, dem::reference_material(), dem::benchmark_numerics(), cfg);
      if (t == 1) one = r.us_per_particle_step;
      std::printf("%s speedup=%.2f\n", dem::to_string(r).c_str(), one / r.us_per_particle_step);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

int command_bench(const Options& o, const Comm& comm) {
  check_omp_environment(comm);
  if (comm.rank != 0) return 0;
  const int max_threads = omp_get_max_threads();
  if (o.bench == "mpm") {
    const std::int64_t points = o.bench_size > 0 ? o.bench_size : 100000;
    const int steps = o.bench_steps > 0 ? o.bench_steps : 20;
    // The rank-0 cost per step of a scene with the issue-15 features on (docs/design/mpm.md).
    const mpm::SceneFeatures features;
    std::printf(
        "# mpm scene: rank-0 MPM cost per step, elastic column, plane strain %s, mass scaling "
        "%g, gravity %s, energy accounting on, %s\n",
        features.plane_strain ? "on" : "off", features.mass_scaling,
        features.gravity ? "on" : "off",
        features.walls ? "rough base wall + gate removed half-way, reactions summed every step"
                       : "base nodes held");
    for (const std::int64_t n : o.bench_size > 0 ? std::vector<std::int64_t>{o.bench_size}
                                                 : std::vector<std::int64_t>{1000, 10000, 100000}) {
      for (int t = 1; t <= std::max(2, max_threads); t *= 2) {
        std::printf("%s\n",
                    mpm::to_string(mpm::run_scene_benchmark(n, t, steps, features)).c_str());
        std::fflush(stdout);
      }
    }
    std::printf("# mpm: material-point updates per second, USF, elastic block under gravity\n");
    for (const auto& shape : mpm::kShapeKindNames) {
      for (int t = 1; t <= std::max(2, max_threads); t *= 2) {
        const auto r = mpm::run_benchmark(points, t, steps, std::string(shape.name));
        std::printf("%s\n", mpm::to_string(r).c_str());
      }
    }
    return 0;
  }
  return bench_dem(o, max_threads);
}

}  // namespace app
