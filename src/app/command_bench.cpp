// `mpmxdem bench dem|mpm`: performance figures on 1 and 2 threads (and more if available).
// Benchmarks print figures; they are never tests.
#include <fmt/format.h>
#include <omp.h>

#include <cstdio>

#include "app/commands.hpp"
#include "mpm/benchmark.hpp"

namespace app {

int command_bench(const Options& o, const Comm& comm) {
  if (comm.rank != 0) return 0;
  const int max_threads = omp_get_max_threads();
  if (o.bench == "mpm") {
    const std::int64_t points = o.bench_size > 0 ? o.bench_size : 100000;
    const int steps = o.bench_steps > 0 ? o.bench_steps : 20;
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
