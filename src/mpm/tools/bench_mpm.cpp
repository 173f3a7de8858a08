// bench_mpm: material-point updates per second of the MPM step, 1 and 2 threads.
// Run: build/src/mpm/bench_mpm [points=100000] [steps=20]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "mpm/benchmark.hpp"
#include "mpm/shape_function.hpp"

int main(int argc, char** argv) {
  try {
    const long long n = argc > 1 ? std::atoll(argv[1]) : 100000;
    const int steps = argc > 2 ? std::atoi(argv[2]) : 20;
    for (const auto& shape : mpm::kShapeKindNames) {
      for (const int threads : {1, 2}) {
        std::printf(
            "%s\n",
            mpm::to_string(mpm::run_benchmark(n, threads, steps, std::string(shape.name))).c_str());
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mpm: %s\n", e.what());
    return 1;
  }
  return 0;
}
