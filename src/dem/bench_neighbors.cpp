// bench_neighbors: what a neighbour-list build costs against a DEM step (a program, never a test).
// Usage: bench_neighbors [packing.txt] [reps=200] [heap=keep|default]
// The packing (default: the 1000-sphere reference) is prepared as an RVE, then its list is built
// `reps` times from the prepared state's contacts (dem::build_pairs, as a rebuild does) between
// DEM steps of a copy; prints the medians. heap=keep: freed memory stays with the process
// (common::keep_freed_memory, what `mpmxdem` does); default: glibc's own policy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "common/heap.hpp"
#include "dem/benchmark.hpp"
#include "dem/neighbor_search.hpp"
#include "dem/packing_io.hpp"
#include "dem/reference_material.hpp"
#include "dem/rve.hpp"

namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string heap = argc > 3 ? argv[3] : "keep";
    if (heap != "keep" && heap != "default") {
      std::fprintf(stderr, "bench_neighbors: heap '%s': must be keep or default\n", heap.c_str());
      return 2;
    }
    if (heap == "keep" && !common::keep_freed_memory()) {
      std::fprintf(stderr, "bench_neighbors: the C library refused the heap settings\n");
    }
    const std::string path =
        (argc > 1 && argv[1][0] != 0) ? argv[1] : dem::reference_packing_path();
    const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 200;
    dem::RveParams p;
    p.material = dem::reference_material();
    const dem::Rve rve(dem::read_packing(path), p);
    const dem::Simulation& sim = rve.simulation();
    dem::Simulation stepped = sim;
    std::vector<double> build;
    std::vector<double> step;
    using clock = std::chrono::steady_clock;
    for (int r = 0; r < reps; ++r) {
      dem::Contacts c = sim.contacts();
      dem::VerletState vs = sim.verlet();
      const auto t0 = clock::now();
      dem::build_pairs(sim.spheres(), sim.cell(), c, vs);
      const auto t1 = clock::now();
      stepped.step();
      const auto t2 = clock::now();
      build.push_back(std::chrono::duration<double>(t1 - t0).count());
      step.push_back(std::chrono::duration<double>(t2 - t1).count());
    }
    const double b = median(build);
    const double s = median(step);
    std::printf(
        "spheres=%zu pairs=%zu heap=%s reps=%d build_us=%.1f step_us=%.1f build/step=%.1f\n",
        sim.spheres().size(), sim.contacts().size(), heap.c_str(), reps, 1e6 * b, 1e6 * s, b / s);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_neighbors: %s\n", e.what());
    return 1;
  }
}
