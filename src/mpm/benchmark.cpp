// MPM throughput benchmark (see header).
#include "mpm/benchmark.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "common/errors.hpp"
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

std::string to_string(const BenchmarkResult& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "shape=%s points=%lld threads=%d steps=%lld seconds=%.3f updates/s=%.4g",
                r.shape.c_str(), static_cast<long long>(r.points), r.threads,
                static_cast<long long>(r.steps), r.seconds, r.updates_per_second);
  return buf;
}

}  // namespace mpm
