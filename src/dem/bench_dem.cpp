// bench_dem: standalone run of dem::run_benchmark.
// Usage: bench_dem [packing.txt] [tiles=1] [threads=1] [steps=3000] [law=cohfrict]
// law: cohfrict (the reference material) or hertz_mindlin (the material of
// jobs/triaxial_dem_hertz_mindlin.toml; an empty packing then means its packing,
// jobs/packings/packing_N1000_hertz_mindlin.txt).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "common/choice_table.hpp"
#include "dem/benchmark.hpp"
#include "dem/params.hpp"
#include "dem/reference_material.hpp"

int main(int argc, char** argv) {
  try {
    const std::string name = argc > 5 ? argv[5] : "cohfrict";
    const auto law = common::value_of(dem::kContactLawNames, name);
    if (!law) {
      std::fprintf(stderr, "bench_dem: law '%s': must be one of %s\n", name.c_str(),
                   common::names_list(dem::kContactLawNames).c_str());
      return 2;
    }
    dem::Material mat = dem::reference_material();
    std::string fallback = dem::reference_packing_path();
    if (*law == dem::ContactLawKind::hertz_mindlin) {
      mat = dem::hertz_mindlin_reference_material();
      fallback = fallback.substr(0, fallback.rfind('/')) + "/packing_N1000_hertz_mindlin.txt";
    }
    const std::string path = (argc > 1 && argv[1][0] != 0) ? argv[1] : fallback;
    dem::BenchmarkConfig cfg;
    cfg.tiles = argc > 2 ? std::atoi(argv[2]) : 1;
    cfg.threads = argc > 3 ? std::atoi(argv[3]) : 1;
    cfg.steps = argc > 4 ? std::atoll(argv[4]) : 3000;
    const auto r = dem::run_benchmark(dem::read_packing(path), mat, dem::benchmark_numerics(), cfg);
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
