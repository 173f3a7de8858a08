// DEM speed benchmark (triaxial shearing of a tiled packing).
#include "dem/benchmark.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <limits>

#include "dem/element_test.hpp"
#include "dem/loading.hpp"
#include "dem/rve.hpp"
#include "dem/threads.hpp"

namespace dem {

namespace {
template <class V>
double bytes(const V& v) {
  return static_cast<double>(v.capacity() * sizeof(typename V::value_type));
}

// FNV-1a over the object representation of doubles (bit patterns, -0 and +0 differ).
class Fnv {
 public:
  void add(const double* p, std::size_t n) {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    for (std::size_t k = 0; k < n * sizeof(double); ++k) {
      h_ = (h_ ^ b[k]) * 1099511628211ULL;
    }
  }
  template <class V>
  void add_vec3(const V& v) {
    for (const auto& e : v) add(e.data(), 3);
  }
  [[nodiscard]] std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

std::uint64_t state_hash(const Simulation& sim) {
  Fnv f;
  const Spheres& s = sim.spheres();
  f.add_vec3(s.x);
  f.add_vec3(s.u);
  f.add_vec3(s.w);
  f.add_vec3(s.force);
  f.add_vec3(s.torque);
  f.add(sim.cell().h.data(), 9);
  f.add(sim.stress().data(), 9);
  const Contacts& c = sim.contacts();
  for (std::size_t p = 0; p < c.size(); ++p) {
    const CohFrictHistory h = c.hist.get(p);
    f.add(h.normal.data(), 3);
    f.add(h.shear.data(), 3);
    f.add(h.roll.data(), 3);
    f.add(h.twist.data(), 3);
  }
  f.add_vec3(c.force);
  f.add_vec3(c.torque_i);
  f.add_vec3(c.torque_j);
  for (std::size_t p = 0; p < c.size(); ++p) {
    // Pairs in contact only: nothing reads the branch of a pair apart.
    if (c.active[p] != 0) f.add(c.branch[p].data(), 3);
  }
  for (std::size_t p = 0; p < c.size(); ++p) {
    const double fn = sim.normal_force(p);  // stored per pair before 2026-11-26: the same hashes
    f.add(&fn, 1);
  }
  const double dt = sim.dt();
  f.add(&dt, 1);
  return f.value();
}
}  // namespace

std::string reference_packing_path() { return MPMXDEM_REFERENCE_PACKING; }

std::string to_string(const BenchmarkResult& r) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "spheres=%lld threads=%d team=%d steps=%lld ms/step=%.4f us/particle-step=%.4f "
                "contacts/sphere=%.3f pairs/sphere=%.3f dt=%.4g rebuilds=%lld hash=%016llx",
                static_cast<long long>(r.spheres), r.threads, r.team,
                static_cast<long long>(r.steps), r.ms_per_step, r.us_per_particle_step,
                r.contacts_per_sphere, r.pairs_per_sphere, r.dt, static_cast<long long>(r.rebuilds),
                static_cast<unsigned long long>(r.state_hash));
  return buf;
}

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
  const std::clock_t c0 = std::clock();
  advance(sim, &ctl, cfg.steps);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  const auto spheres = static_cast<std::int64_t>(pk.r.size());
  const int team = one_thread(spheres) ? 1 : team_size(spheres);
  omp_set_num_threads(old_threads);

  BenchmarkResult r;
  const auto n = static_cast<double>(pk.r.size());
  r.spheres = static_cast<std::int64_t>(pk.r.size());
  r.threads = cfg.threads;
  r.team = team;
  r.steps = cfg.steps;
  r.wall_s = wall;
  r.cpu_s = cpu;
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
  b += bytes(c.i) + bytes(c.j) + bytes(c.k) + bytes(c.active) + bytes(c.tan_phi) +
       bytes(c.hist.normal[0]) * 12 + bytes(c.force) + bytes(c.torque_i) + bytes(c.torque_j) +
       bytes(c.branch) + bytes(c.sphere_offset) + bytes(c.sphere_pairs) + bytes(sim.verlet().x_ref);
  r.bytes_per_sphere = b / n;
  r.state_hash = state_hash(sim);
  // critical_dt is called once per MPM step for every RVE: timed on its own (one thread).
  r.critical_dt = sim.critical_dt();
  r.us_critical_dt = std::numeric_limits<double>::infinity();
  for (int batch = 0; batch < 5; ++batch) {
    const auto b0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 100; ++k) {
      volatile double dt = sim.critical_dt();  // volatile: every call is made
      (void)dt;
    }
    const double us =
        1e6 * std::chrono::duration<double>(std::chrono::steady_clock::now() - b0).count() / 100.0;
    r.us_critical_dt = std::min(r.us_critical_dt, us);
  }
  return r;
}

}  // namespace dem
