// DEM speed benchmark: tile a packing n x n x n and time drained triaxial shearing at
// I = 2.5e-4 (the app wires it to `mpmxdem bench dem`; bench_dem runs it standalone).
#pragma once

#include <cstdint>
#include <string>

#include "dem/packing_io.hpp"
#include "dem/params.hpp"

namespace dem {

struct BenchmarkConfig {
  int tiles = 1;                    ///< n of the n x n x n tiling [-]
  int threads = 1;                  ///< OpenMP threads [-]
  std::int64_t warmup_steps = 500;  ///< untimed steps first [-]
  std::int64_t steps = 3000;        ///< timed steps [-]
  double inertial_number = 2.5e-4;  ///< I [-]
  double confining = 1e5;           ///< lateral stress [Pa]
};

struct BenchmarkResult {
  std::int64_t spheres = 0;
  int threads = 0;
  int team = 0;            ///< threads the step ran on: at most spheres / kSpheresPerThread
  std::int64_t steps = 0;  ///< timed steps
  double wall_s = 0.0;     ///< timed wall seconds [s]
  double cpu_s = 0.0;      ///< process CPU seconds of the timed steps, all threads (std::clock) [s]
  double ms_per_step = 0.0;           ///< [ms]
  double us_per_particle_step = 0.0;  ///< [us]
  double contacts_per_sphere = 0.0;   ///< active contacts / N at the end [-]
  double pairs_per_sphere = 0.0;      ///< Verlet pairs / N at the end [-]
  double dt = 0.0;                    ///< DEM time step [s]
  double bytes_per_sphere = 0.0;      ///< heap bytes of spheres + pairs + Verlet state / N [B]
  std::int64_t rebuilds = 0;          ///< neighbour rebuilds during the run
  double critical_dt = 0.0;           ///< Simulation::critical_dt() of the final state [s]
  double us_critical_dt = 0.0;        ///< its cost: the fastest of 5 batches of 100 calls [us]
  /// FNV-1a hash of the bits of the final state (positions, velocities, spins, cell, contact
  /// history and forces, the branches of the pairs in contact, stress): equal hashes =
  /// bit-identical runs (thread counts, builds). (Before 2026-11-26 it hashed the branch of every
  /// pair: the hashes of older builds differ.)
  std::uint64_t state_hash = 0;
};

/// The reference packing (1000 spheres at 100 kPa, e = 0.562) of the source tree this library was
/// built from: jobs/packings/packing_N1000_e0.562.txt.
[[nodiscard]] std::string reference_packing_path();

/// One line of figures: spheres=... threads=... steps=... ms/step=... us/particle-step=...
/// contacts/sphere=... pairs/sphere=... dt=... rebuilds=... hash=... (`mpmxdem bench dem`).
[[nodiscard]] std::string to_string(const BenchmarkResult& r);

/// The numerics of the benchmark: the defaults with the fixed skin (skin_factor 0.1), so that
/// its figures measure the kernel as they always did (the adaptive skin thins the lists of its
/// slow triaxial and would change what is measured: docs/design/dem.md "Speed").
[[nodiscard]] inline Numerics benchmark_numerics() {
  Numerics n;
  n.skin_min_factor = 0.0;
  return n;
}

/// Run the benchmark. Deterministic results, wall time of course not.
[[nodiscard]] BenchmarkResult run_benchmark(const Packing& base, const Material& mat,
                                            const Numerics& num, const BenchmarkConfig& cfg);

}  // namespace dem
