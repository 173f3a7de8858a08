// bench_dem: standalone run of dem::run_benchmark.
// Usage: bench_dem [packing.txt] [tiles=1] [threads=1] [steps=3000]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "dem/benchmark.hpp"
#include "dem/reference_material.hpp"

int main(int argc, char** argv) {
  try {
    const std::string path =
        (argc > 1 && argv[1][0] != 0) ? argv[1] : dem::reference_packing_path();
    dem::BenchmarkConfig cfg;
    cfg.tiles = argc > 2 ? std::atoi(argv[2]) : 1;
    cfg.threads = argc > 3 ? std::atoi(argv[3]) : 1;
    cfg.steps = argc > 4 ? std::atoll(argv[4]) : 3000;
    const auto r = dem::run_benchmark(dem::read_packing(path), dem::reference_material(),
                                      dem::benchmark_numerics(), cfg);
    std::printf("spheres %lld threads %d team %d steps %lld wall %.3f s cpu %.3f s\n",
                static_cast<long long>(r.spheres), r.threads, r.team,
                static_cast<long long>(r.steps), r.wall_s, r.cpu_s);
    std::printf("ms/step %.4f  us/particle-step %.4f  contacts/sphere %.3f  pairs/sphere %.3f\n",
                r.ms_per_step, r.us_per_particle_step, r.contacts_per_sphere, r.pairs_per_sphere);
    std::printf("dt %.4g s  bytes/sphere %.0f  rebuilds %lld  hash %016llx\n", r.dt,
                r.bytes_per_sphere, static_cast<long long>(r.rebuilds),
                static_cast<unsigned long long>(r.state_hash));
    std::printf("critical_dt %a s  %.2f us per call\n", r.critical_dt, r.us_critical_dt);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dem: %s\n", e.what());
    return 1;
  }
}
