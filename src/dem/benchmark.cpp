// DEM speed benchmark (triaxial shearing of a tiled packing).
#include "dem/benchmark.hpp"

#include <omp.h>

#include <chrono>

#include "dem/element_test.hpp"
#include "dem/loading.hpp"
#include "dem/rve.hpp"

namespace dem {

namespace {
template <class V>
double bytes(const V& v) {
  return static_cast<double>(v.capacity() * sizeof(typename V::value_type));
}
}  // namespace

BenchmarkResult run_benchmark(const Packing& base, const Material& mat, const Numerics& num,
                              const BenchmarkConfig& cfg) {
  const int old_threads = omp_get_max_threads();
  omp_set_num_threads(cfg.threads);
  const Packing pk = tile_packing(base, cfg.tiles);
  Simulation sim = make_simulation(pk, mat, num);
  DrainedTriaxial test;
  test.axial_rate =
      strain_rate(cfg.inertial_number, mass_median_diameter(pk.r), mat.density, cfg.confining);
  test.confining = cfg.confining;
  MixedController ctl(triaxial_servo(test));
  advance(sim, &ctl, cfg.warmup_steps);
  const std::int64_t builds0 = sim.verlet().builds;
  const auto t0 = std::chrono::steady_clock::now();
  advance(sim, &ctl, cfg.steps);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  omp_set_num_threads(old_threads);

  BenchmarkResult r;
  const auto n = static_cast<double>(pk.r.size());
  r.spheres = static_cast<std::int64_t>(pk.r.size());
  r.threads = cfg.threads;
  r.steps = cfg.steps;
  r.wall_s = wall;
  r.ms_per_step = 1e3 * wall / static_cast<double>(cfg.steps);
  r.us_per_particle_step = 1e6 * wall / static_cast<double>(cfg.steps) / n;
  const Contacts& c = sim.contacts();
  std::int64_t nc = 0;
  for (auto a : c.active) nc += a;
  r.contacts_per_sphere = static_cast<double>(nc) / n;
  r.pairs_per_sphere = static_cast<double>(c.size()) / n;
  r.dt = sim.dt();
  r.rebuilds = sim.verlet().builds - builds0;
  const Spheres& s = sim.spheres();
  double b = bytes(s.x) + bytes(s.u) + bytes(s.w) + bytes(s.force) + bytes(s.torque) + bytes(s.r) +
             bytes(s.m) + bytes(s.inertia) + bytes(s.fixed);
  b += bytes(c.i) + bytes(c.j) + bytes(c.k) + bytes(c.active) + bytes(c.props) + bytes(c.hist) +
       bytes(c.force) + bytes(c.torque_i) + bytes(c.torque_j) + bytes(c.branch) + bytes(c.fn) +
       bytes(c.sphere_offset) + bytes(c.sphere_pairs) + bytes(sim.verlet().x_ref);
  r.bytes_per_sphere = b / n;
  return r;
}

}  // namespace dem
