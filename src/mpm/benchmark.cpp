// MPM throughput benchmark (see header).
#include "mpm/benchmark.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "common/errors.hpp"
#include "mpm/energy.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace mpm {

BenchmarkResult run_benchmark(std::int64_t num_points, int threads, int steps,
                              const std::string& shape) {
  if (num_points < 8 || threads < 1 || steps < 1) {
    throw common::InputError("mpm benchmark: need >= 8 points, >= 1 thread and >= 1 step");
  }
  const double cells_wanted = static_cast<double>(num_points) / 8.0;
  const int side = std::max(1, static_cast<int>(std::lround(std::cbrt(cells_wanted))));
  const int height = std::max(1, static_cast<int>(std::ceil(cells_wanted / (side * side))));
  const int pad = 2;
  SolverConfig cfg;
  cfg.shape = shape_kind_from_string(shape);
  cfg.grid.origin = common::Vec3::Constant(-pad * 0.1);
  cfg.grid.spacing = common::Vec3::Constant(0.1);
  cfg.grid.cells = common::Vec3i(side + 2 * pad, side + 2 * pad, height + 2 * pad);
  cfg.gravity = common::Vec3(0.0, 0.0, -9.81);
  cfg.cfl = 0.3;
  const double density = 2000.0;
  LinearElastic material(1e7, 0.3, density);
  MaterialPoints points;
  fill_box(points, cfg.grid, common::Vec3::Zero(), common::Vec3(side, side, height) * 0.1, 2,
           density, 0);
  Solver solver(cfg, std::move(points), {&material});
  solver.add_constraint({common::Vec3::Constant(-1.0),
                         common::Vec3(10.0 * side, 10.0 * side, 0.0),
                         {true, true, true},
                         common::Vec3::Zero(),
                         {}});

  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  BenchmarkResult r;
  try {
    solver.run(2);
    const auto t0 = std::chrono::steady_clock::now();
    solver.run(steps);
    const auto t1 = std::chrono::steady_clock::now();
    r.seconds = std::chrono::duration<double>(t1 - t0).count();
  } catch (...) {
    omp_set_num_threads(saved);
    throw;
  }
  omp_set_num_threads(saved);
  r.points = static_cast<std::int64_t>(solver.points().size());
  r.threads = threads;
  r.steps = steps;
  r.updates_per_second = static_cast<double>(r.points) * steps / r.seconds;
  r.shape = shape;
  return r;
}

namespace {

/// Runs f with `threads` OpenMP threads, restoring the previous count (also on an exception).
template <class F>
void with_threads(int threads, F&& f) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  try {
    f();
  } catch (...) {
    omp_set_num_threads(saved);
    throw;
  }
  omp_set_num_threads(saved);
}

/// The scene's base: held nodes (every node at or below z = 0), or (walls) a rigid rough wall on
/// z = 0 and a gate at x = x_gate removed half-way through the `steps` timed steps
/// (SceneFeatures::walls).
void add_scene_base(Solver& solver, bool walls, double x_gate, int steps) {
  if (walls) {
    VelocityConstraint base{common::Vec3(-1e3, -1e3, 0.0), common::Vec3(1e3, 1e3, 0.0), {}, {}, {}};
    base.wall = {2, -1, 10.0, WallContact::fixed};
    base.name = "base";
    solver.add_constraint(base);
    VelocityConstraint gate{
        common::Vec3(x_gate, -1e3, 0.0), common::Vec3(x_gate, 1e3, 1e3), {}, {}, {}};
    gate.wall = {0, 1, 0.0, WallContact::no_penetration};
    gate.until = (2 + steps / 2) * solver.next_dt();
    gate.name = "gate";
    solver.add_constraint(gate);
  } else {
    solver.add_constraint({common::Vec3::Constant(-1e3),
                           common::Vec3(1e3, 1e3, 0.0),
                           {true, true, true},
                           common::Vec3::Zero(),
                           {}});
  }
}

}  // namespace

SceneBenchmarkResult run_scene_benchmark(std::int64_t num_points, int threads, int steps,
                                         const SceneFeatures& features) {
  if (num_points < 8 || threads < 1 || steps < 1) {
    throw common::InputError("mpm scene benchmark: need >= 8 points, >= 1 thread and >= 1 step");
  }
  const double h = 0.1;
  const int pad = 2;
  SolverConfig cfg;
  cfg.grid.spacing = common::Vec3::Constant(h);
  cfg.cfl = 0.5;
  cfg.damping = 0.1;
  cfg.mass_scaling = features.mass_scaling;
  if (features.gravity) cfg.gravity = common::Vec3(0.0, 0.0, -9.81);
  // A square column: nx x nz cells of 4 points (plane strain) or nx x nx x nz cells of 8.
  int nx = 1;
  int ny = 1;
  int nz = 1;
  if (features.plane_strain) {
    cfg.plane_strain_axis = 1;
    nx = std::max(1, static_cast<int>(std::lround(std::sqrt(num_points / 4.0))));
    nz = std::max(1, static_cast<int>(std::lround(num_points / (4.0 * nx))));
    cfg.grid.origin = common::Vec3(-pad * h, 0.0, -pad * h);
    cfg.grid.cells = common::Vec3i(nx + 2 * pad, 1, nz + 2 * pad);
  } else {
    nx = std::max(1, static_cast<int>(std::lround(std::cbrt(num_points / 8.0))));
    ny = nx;
    nz = std::max(1, static_cast<int>(std::lround(num_points / (8.0 * nx * ny))));
    cfg.grid.origin = common::Vec3::Constant(-pad * h);
    cfg.grid.cells = common::Vec3i(nx + 2 * pad, ny + 2 * pad, nz + 2 * pad);
  }
  const double density = 2000.0;
  LinearElastic material(1e7, 0.3, density);
  MaterialPoints points;
  fill_box(points, cfg.grid, common::Vec3::Zero(), common::Vec3(nx, ny, nz) * h,
           features.plane_strain ? common::Vec3i(2, 1, 2) : common::Vec3i(2, 2, 2), density, 0);
  Solver solver(cfg, std::move(points), {&material});
  add_scene_base(solver, features.walls, nx * h, steps);
  SceneBenchmarkResult r;
  with_threads(threads, [&] {
    auto step = [&] {
      solver.step();
      const Energies e = solver.energies();       // the coupled run's quasi-static watch
      common::Vec3 total = common::Vec3::Zero();  // the reactions, as the results rows read them
      for (const common::Vec3& f : solver.reactions()) total += f;
      if (!std::isfinite(e.kinetic) || !total.allFinite())
        throw common::NumericalError("mpm scene benchmark: blow-up");
    };
    step();
    step();
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) step();
    const auto t1 = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    r.ms_per_step = 1e3 * seconds / steps;
  });
  r.points = static_cast<std::int64_t>(solver.points().size());
  r.nodes = cfg.grid.num_nodes();
  r.threads = threads;
  r.steps = steps;
  r.ns_per_point_step = 1e6 * r.ms_per_step / static_cast<double>(r.points);
  return r;
}

std::string to_string(const SceneBenchmarkResult& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "points=%lld nodes=%lld threads=%d steps=%lld ms/step=%.3f ns/point-step=%.1f",
                static_cast<long long>(r.points), static_cast<long long>(r.nodes), r.threads,
                static_cast<long long>(r.steps), r.ms_per_step, r.ns_per_point_step);
  return buf;
}

std::string to_string(const BenchmarkResult& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "shape=%s points=%lld threads=%d steps=%lld seconds=%.3f updates/s=%.4g",
                r.shape.c_str(), static_cast<long long>(r.points), r.threads,
                static_cast<long long>(r.steps), r.seconds, r.updates_per_second);
  return buf;
}

}  // namespace mpm
