// triax_dem: drained triaxial validation study on a packing (not a test; docs/design/dem.md).
// Re-equilibrates at the confining pressure, then shears at inertial number I to a final axial
// strain, printing one CSV row per 0.1 % of axial strain (compression positive, as YADE's CSV).
// Usage: triax_dem [packing.txt] [final_eps_a=0.25] [I=2.5e-4] [threads=1]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "dem/element_test.hpp"
#include "dem/loading.hpp"
#include "dem/measures.hpp"
#include "dem/reference_material.hpp"
#include "dem/rve.hpp"

int main(int argc, char** argv) {
  try {
    const std::string path = (argc > 1 && argv[1][0] != 0) ? argv[1] : MPMXDEM_BENCH_PACKING;
    const double eps_end = argc > 2 ? std::atof(argv[2]) : 0.25;
    const double inertial = argc > 3 ? std::atof(argv[3]) : 2.5e-4;
    omp_set_num_threads(argc > 4 ? std::atoi(argv[4]) : 1);
    const dem::Material mat = dem::reference_material();
    const double p0 = 1e5;
    const dem::Packing pk = dem::read_packing(path);
    dem::Simulation sim = dem::make_simulation(pk, mat, dem::Numerics{});
    dem::EquilibriumTarget et;
    et.pressure = p0;
    et.stress_tol = 0.005;
    et.unbalanced_tol = 0.005;
    const auto eq_steps = dem::equilibrate(sim, et);
    std::fprintf(stderr, "re-equilibrated in %lld steps\n", static_cast<long long>(eq_steps));
    dem::DrainedTriaxial test;
    test.axial_rate = dem::strain_rate(inertial, dem::mass_median_diameter(pk.r), mat.density, p0);
    test.confining = p0;
    test.eps_end = eps_end;
    std::printf("step,time,dt,eps_a,eps_v,p,q,sig_a,sig_r,e,Z,Zm,unbalanced,wall_s\n");
    const auto t0 = std::chrono::steady_clock::now();
    double next = 0.0;
    dem::run_drained_triaxial(
        sim, test, [&](const dem::Simulation& s, const dem::TriaxialProgress& now) {
          if (now.eps_a < next && !now.last) return;
          const dem::Measures m = dem::measure(s);
          const double sa = -m.stress(2, 2);
          const double sr = -0.5 * (m.stress(0, 0) + m.stress(1, 1));
          const double wall =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          std::printf("%lld,%.8e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6f,%.5f,%.5f,%.4e,%.2f\n",
                      static_cast<long long>(s.steps()), s.time(), s.dt(), now.eps_a, now.eps_v,
                      m.p, sa - sr, sa, sr, m.void_ratio, m.z, m.z_mech, m.unbalanced, wall);
          std::fflush(stdout);
          next += 0.001;
        });
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "triax_dem: %s\n", e.what());
    return 1;
  }
}
