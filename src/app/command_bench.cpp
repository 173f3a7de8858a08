// `mpmxdem bench dem|mpm`: performance figures on 1 and 2 threads (and more if available).
// Benchmarks print figures; they are never tests.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "app/commands.hpp"
#include "mpm/benchmark.hpp"

namespace app {

int command_bench(const Options& o, const Comm& comm) {
  if (comm.rank != 0) return 0;
  const int max_threads = omp_get_max_threads();
  if (o.bench == "mpm") {
    const std::int64_t points = o.bench_size > 0 ? o.bench_size : 100000;
    const int steps = o.bench_steps > 0 ? o.bench_steps : 20;
    // The rank-0 cost per step of a scene with the issue-15 features on (docs/mpm.md).
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
    for (const char* shape : {"linear", "ugimp", "bspline2"}) {
      for (int t = 1; t <= std::max(2, max_threads); t *= 2) {
        const auto r = mpm::run_benchmark(points, t, steps, shape);
        std::printf("%s\n", mpm::to_string(r).c_str());
      }
    }
    return 0;
  }
  std::printf("bench dem: not available in this build yet\n");
  return 1;
}

}  // namespace app
