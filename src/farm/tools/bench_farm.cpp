// bench_farm: figures of the RVE farm (a program, never a test). Run under mpiexec, e.g.
//   mpiexec -n 2 --bind-to none bench_farm overhead [--wait auto|spin|sleep] [--steps 10]
//       [--output-every 10] (rows of results.h5: the paper's job writes every 10th step)
//   mpiexec -n 2 --bind-to none bench_farm balance  [--micro elastic|dem] [--rves 32|12]
//       [--steps 20]
//   mpiexec -n 2 --bind-to none bench_farm checkpoint [--rves 8] [--micro dem|elastic]
//       [--owners metis|blocks]
//   mpiexec -n 4 --bind-to none bench_farm exchange --rves 10000 [--steps 50] [--migrate 1]
//   mpiexec -n 2 --bind-to none bench_farm move [--steps 40] [--reps 20] (a migration's cost,
//       then its phases on rank 0: save, serialise, deserialise, load)
//   bench_farm partition --rves 10000 [--parts 1024] [--bytes-per-rve 266000]
//       [--perturb noise|overload] [--overload 0.1] [--threshold 1.0]
// (exchange, partition, checkpoint --micro elastic: what grows with the RVE count;
// docs/validation/scaling.md) Options: --speed <x> (platen speed in units of eq. 13), --packing
// <file> (DEM packing; default: the 1000-sphere reference of jobs/packings),
// --omp-over-rves 0|1, --rank0-rves 0|1 (0: rank 0 runs the MPM only), --partition spread|cells,
// --wait auto|spin|sleep (auto: spin unless threads share cores). docs/design/farm.md, Benchmarks.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_farm_args.hpp"
#include "common/state_store.hpp"
#include "dem/packing_io.hpp"
#include "dem/reference_material.hpp"
#include "farm/dem_micro.hpp"
#include "farm/driver.hpp"
#include "farm/elastic_micro.hpp"
#include "farm/partition.hpp"
#include "farm/rebalance.hpp"
#include "farm/rve_farm.hpp"
#include "mpm/boundary.hpp"
#include "mpm/material_points.hpp"

namespace {

using bench_farm::Args;
using bench_farm::lattice;
using bench_farm::Lattice;
using bench_farm::now;
using common::Mat3;
using common::Vec3;

int rank_of(MPI_Comm c) {
  int r = 0;
  MPI_Comm_rank(c, &r);
  return r;
}
int size_of(MPI_Comm c) {
  int s = 1;
  MPI_Comm_size(c, &s);
  return s;
}

farm::MicroKind dem_kind(const std::string& packing_file) {
  const dem::Packing pk = dem::read_packing(packing_file);
  farm::DemMicroParams p;
  p.rve.material = dem::reference_material();
  return farm::DemMicro::kind(p, [pk](std::int64_t) { return pk; });
}

farm::FarmOptions farm_options(const Args& a) {
  farm::FarmOptions o;
  o.wait = farm::wait_mode_from(a.get("wait", "auto"));
  o.omp_over_rves = a.get("omp-over-rves", "1") == "1";
  o.rank0_rves = a.get("rank0-rves", "1") == "1";
  o.partition = farm::parse_partition_style(a.get("partition", "spread"));
  return o;
}

// The paper's single-cell triaxial as jobs/triaxial_mpmxdem.toml sets it up (8 fixed points, 1 m
// cell, USF, 100 kPa, platen at eq. 13 speed, 3-2-1 support of two bottom nodes).
farm::CoupledConfig triaxial(const std::string& dir, std::int64_t steps, farm::MicroKind kind,
                             double speed) {
  farm::CoupledConfig c;
  c.solver.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i::Ones()};
  c.solver.damping = 0.2;
  c.solver.cfl = 0.5;
  c.solver.stress_update = mpm::StressUpdate::usf;
  c.solver.move_points = false;
  const double rho = 1600.0;
  const double p = 100e3;
  mpm::fill_box(c.points, c.solver.grid, Vec3::Zero(), Vec3::Ones(), 2, rho, 0);
  for (auto& s : c.points.stress) s = -p * Mat3::Identity();
  const double v_top = -speed * 2.5e-4 * std::sqrt(p / rho);
  c.constraints.push_back(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  c.constraints.push_back(
      {Vec3(-10, -10, 1), Vec3::Constant(10), {false, false, true}, Vec3(0, 0, v_top), {}});
  c.constraints.push_back(mpm::node_constraint(c.solver.grid, Vec3::Zero(), {true, true, false}));
  c.constraints.push_back(mpm::node_constraint(c.solver.grid, Vec3(1, 0, 0), {false, true, false}));
  for (int axis : {0, 1}) {
    for (int side : {-1, 1}) c.tractions.push_back({axis, side, p, Vec3::Zero()});
  }
  c.max_steps = steps;
  c.micro = std::move(kind);
  c.job_text = "# bench_farm\n";
  c.output.dir = dir;
  c.output.log_every_s = 1e9;
  c.checkpoint.at_end = false;
  std::filesystem::create_directories(dir);
  return c;
}

void overhead(const Args& a, MPI_Comm comm) {
  const std::int64_t steps = std::stoll(a.get("steps", "10"));
  farm::CoupledConfig c =
      triaxial("/tmp/bench_farm_overhead", steps,
               dem_kind(a.get("packing", MPMXDEM_DEFAULT_PACKING)), std::stod(a.get("speed", "1")));
  c.farm = farm_options(a);
  c.output.every = std::stoll(a.get("output-every", "10"));
  // Per window of output.every steps (each window writes one results row): the share of the
  // loop's wall time not spent in the critical rank's RVEs. The median over windows is robust to
  // this VM's stolen time slices, which land on a few windows only.
  std::vector<double> window_share;
  double last_wall = -1.0;
  double last_crit = 0.0;
  double w_wall = 0.0;
  double w_crit = 0.0;
  c.on_step = [&](std::int64_t step, const farm::FarmTimes& t) {
    const double tn = now();
    if (last_wall >= 0.0) {
      w_wall += tn - last_wall;
      w_crit += t.critical_busy - last_crit;
      if (step % c.output.every == 0) {
        window_share.push_back((w_wall - w_crit) / w_wall);
        w_wall = 0.0;
        w_crit = 0.0;
      }
    }
    last_wall = tn;
    last_crit = t.critical_busy;
  };
  const double t0 = now();
  const farm::RunSummary s = farm::run_coupled(c, comm);
  const double total = now() - t0;
  if (rank_of(comm) == 0) {
    const farm::FarmTimes& t = s.times;
    std::printf(
        "overhead: ranks %d, 8 DEM RVEs, %lld MPM steps, platen x%s eq. 13, wait %s "
        "(resolved: %s), omp over RVEs %s, results row every %lld steps\n",
        size_of(comm), static_cast<long long>(s.steps), a.get("speed", "1").c_str(),
        a.get("wait", "auto").c_str(), farm::to_string(s.wait), a.get("omp-over-rves", "1").c_str(),
        static_cast<long long>(c.output.every));
    std::printf(
        "  stepping loop wall          %10.4f s  (%.4f s per MPM step; run incl. set-up %.3f s)\n",
        s.wall_s, s.wall_s / static_cast<double>(steps), total);
    std::printf(
        "  critical RVE busy (max rank) %10.4f s  (migrations incl. start-up %lld, %lld RVEs "
        "moved)\n",
        t.critical_busy, static_cast<long long>(s.migrations),
        static_cast<long long>(s.rves_moved));
    std::printf("  mean RVE busy per rank       %10.4f s  -> balance mean/max %.3f\n", t.mean_busy,
                t.mean_busy / t.critical_busy);
    std::printf("  farm exchange + wait         %10.6f s  (update_stress wall - critical busy)\n",
                t.step_wall - t.critical_busy);
    std::printf("  MPM + outputs                %10.6f s  (loop wall - update_stress wall)\n",
                s.wall_s - t.step_wall);
    std::printf("  => communication + MPM + outputs = %.3f %% of the step time\n",
                100.0 * (s.wall_s - t.critical_busy) / s.wall_s);
    if (!window_share.empty()) {
      std::sort(window_share.begin(), window_share.end());
      auto q = [&](double f) {
        return 100.0 * window_share[static_cast<std::size_t>(f * (window_share.size() - 1))];
      };
      std::printf(
          "  => per window of %lld steps (one results row each, %zu windows): median "
          "%.3f %%, quartiles %.3f-%.3f %%\n",
          static_cast<long long>(c.output.every), window_share.size(), q(0.5), q(0.25), q(0.75));
    }
  }
}

// The RVEs of `balance`: n DEM RVEs of three sizes or n ElasticMicro RVEs of four cost classes
// (by id, scrambled); what: their description.
farm::MicroKind balance_kind(const Args& a, bool dem, int n, std::string& what) {
  farm::MicroKind kind;
  static const int kClass[] = {1, 10, 2, 5, 1, 2, 10, 1, 5, 2, 1, 5};  // scrambled cost classes
  if (dem) {
    const dem::Packing base = dem::read_packing(a.get("packing", MPMXDEM_DEFAULT_PACKING));
    std::map<int, dem::Packing> by_class;  // 1, 2, 4 times the reference's spheres
    by_class[1] = base;
    by_class[2] = dem::tile_packing(base, {2, 1, 1});
    by_class[4] = dem::tile_packing(base, {2, 2, 1});
    auto size_class = [](std::int64_t id) {
      const int c = kClass[id % 12];
      return c == 1 ? 1 : (c == 2 || c == 5 ? 2 : 4);
    };
    farm::DemMicroParams p;
    p.rve.material = dem::reference_material();
    kind = farm::DemMicro::kind(
        p, [by_class, size_class](std::int64_t id) { return by_class.at(size_class(id)); });
    std::int64_t spheres = 0;
    for (int k = 0; k < n; ++k) spheres += size_class(k) * static_cast<std::int64_t>(base.r.size());
    what = std::to_string(n) + " DEM RVEs of " + std::to_string(base.r.size()) + ", " +
           std::to_string(2 * base.r.size()) + " and " + std::to_string(4 * base.r.size()) +
           " spheres (" + std::to_string(spheres) + " in all)";
  } else {
    const std::int64_t base = std::stoll(a.get("substeps", "20000"));
    farm::ElasticMicroParams p;
    p.material.young_modulus = 50e6;
    p.material.poisson_ratio = 0.25;
    p.density = 1600.0;
    kind.create = [p, base](std::int64_t id) {
      farm::ElasticMicroParams q = p;
      q.substeps = base * kClass[id % 12];
      return std::make_unique<farm::ElasticMicro>(id, q);
    };
    kind.load = [](const common::StateReader& r) { return farm::ElasticMicro::load(r); };
    what = std::to_string(n) + " ElasticMicro RVEs of cost classes 1/2/5/10 x " +
           std::to_string(base) + " substeps";
  }
  return kind;
}

// Load balance of RVEs of mixed cost: mean over max of the ranks' RVE busy times, for
// round-robin and METIS partitions. --micro elastic: ElasticMicro RVEs of cost classes 1/2/5/10
// (substeps); --micro dem: DEM RVEs of 1000 / 2000 / 4000 spheres (the reference packing tiled
// 1x1x1, 2x1x1, 2x2x1: the same prepared state in larger cells) under the paper's strain rate.
void balance(const Args& a, MPI_Comm comm) {
  const bool dem = a.get("micro", "elastic") == "dem";
  const int n = std::stoi(a.get("rves", dem ? "12" : "32"));
  const int steps = std::stoi(a.get("steps", "20"));
  const int size = size_of(comm);
  std::string what;
  farm::MicroKind kind = balance_kind(a, dem, n, what);
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  std::vector<Vec3> x(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    ids[static_cast<std::size_t>(k)] = k;
    x[static_cast<std::size_t>(k)] = Vec3((k % 4 + 0.5) / 4.0, ((k / 4) % 4 + 0.5) / 4.0, 0.5);
  }
  const mpm::Grid grid{Vec3::Zero(), Vec3(0.5, 0.5, 1.0), common::Vec3i(2, 2, 1)};
  // The start-up partition: METIS on the models' cost estimates (DEM: particle counts).
  farm::RveFarm f(comm, kind, ids, x, grid, farm_options(a));
  if (f.rank() != 0) {
    f.serve();
    return;
  }
  // DEM: the paper's platen strain rate (eq. 13 over a 1 m sample) and MPM step (CFL 0.5 over
  // 1 m at 336 m/s); elastic: a larger increment.
  std::vector<Mat3> L(static_cast<std::size_t>(n), Mat3::Zero());
  for (auto& l : L) l(2, 2) = dem ? -2.5e-4 * std::sqrt(100e3 / 1600.0) : -1e-2;
  const double dt = dem ? 1.5e-3 : 1e-3;
  std::vector<Mat3> s(static_cast<std::size_t>(n));
  std::vector<double> cost_before = f.cost();
  auto measure = [&](const char* name) {
    const farm::FarmTimes t0 = f.times();
    for (int k = 0; k < steps; ++k) f.update_stress(ids, L, dt, s);
    const farm::FarmTimes t1 = f.times();
    const double crit = t1.critical_busy - t0.critical_busy;
    const double mean = t1.mean_busy - t0.mean_busy;
    // The partition's own balance by the RVEs' measured costs of this phase (no timing noise
    // of single steps): what the partition allows; mean/max busy is what the steps achieved.
    std::vector<double> phase_cost = f.cost();
    for (std::size_t k = 0; k < phase_cost.size(); ++k) phase_cost[k] -= cost_before[k];
    cost_before = f.cost();
    std::printf(
        "  %-24s mean/max busy = %.4f, of the partition %.4f   (critical %.4f s, mean %.4f s, "
        "update_stress wall %.4f s)\n",
        name, mean / crit, 1.0 / farm::imbalance(f.owner(), phase_cost, size), crit, mean,
        t1.step_wall - t0.step_wall);
  };
  std::printf("balance: ranks %d, %s, %d steps each\n", size, what.c_str(), steps);
  measure(dem ? "METIS, particle counts" : "METIS, cost estimates");
  f.migrate_to(farm::partition_round_robin(static_cast<std::size_t>(n), size));
  measure("round-robin");
  const std::vector<double> cost = f.cost();  // measured CPU seconds per RVE so far
  f.migrate_to(farm::partition_metis(farm::cell_graph(grid, x), cost, size));
  measure("METIS, measured costs");
  f.stop();
}

std::vector<std::int64_t> rve_ids(int n) {
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) ids[static_cast<std::size_t>(k)] = k;
  return ids;
}

/// DEM RVEs of the reference packing (--packing) at the points of one unit grid cell (2x2x2,
/// cycled): one METIS graph vertex per RVE, all neighbours.
farm::RveFarm dem_farm_in_one_cell(const Args& a, MPI_Comm comm,
                                   const std::vector<std::int64_t>& ids) {
  std::vector<Vec3> x;
  for (const std::int64_t id : ids) {
    const auto k = static_cast<int>(id % 8);
    x.emplace_back(0.25 + 0.5 * (k & 1), 0.25 + 0.5 * ((k >> 1) & 1), 0.25 + 0.5 * (k >> 2));
  }
  const mpm::Grid grid{Vec3::Zero(), Vec3::Ones(), common::Vec3i::Ones()};
  return farm::RveFarm(comm, dem_kind(a.get("packing", MPMXDEM_DEFAULT_PACKING)), ids, x, grid,
                       farm_options(a));
}

/// Tiny RVEs for counting what grows with their number: ElasticMicro, one substep.
farm::MicroKind tiny_kind() {
  farm::ElasticMicroParams p;
  p.material.young_modulus = 50e6;
  p.material.poisson_ratio = 0.25;
  p.density = 1600.0;
  p.initial_stress = -100e3 * Mat3::Identity();
  return farm::ElasticMicro::kind(p);
}

double max_over_ranks(MPI_Comm comm, double v) {
  double m = 0.0;
  MPI_Allreduce(&v, &m, 1, MPI_DOUBLE, MPI_MAX, comm);
  return m;
}

// Write (best of 3) and collective read of one checkpoint: --micro dem (the reference packing,
// bandwidth) or elastic (tiny RVEs: bytes per RVE of the format's per-RVE overhead).
void checkpoint(const Args& a, MPI_Comm comm) {
  const int n = std::stoi(a.get("rves", "8"));
  const bool dem = a.get("micro", "dem") == "dem";
  const std::vector<std::int64_t> ids = rve_ids(n);
  const std::string path = a.get("path", "/tmp/bench_farm_checkpoint.h5");
  {
    const Lattice lat = lattice(n);
    farm::RveFarm f = dem ? dem_farm_in_one_cell(a, comm, ids)
                          : farm::RveFarm(comm, tiny_kind(), ids, lat.x, lat.grid, farm_options(a));
    if (f.rank() != 0) {
      f.serve();
    } else {
      std::vector<Mat3> L(static_cast<std::size_t>(n), Mat3::Zero());
      for (auto& l : L) l(2, 2) = -0.01;
      std::vector<Mat3> s(static_cast<std::size_t>(n));
      f.update_stress(ids, L, 1e-3, s);  // contacts with history
      // --owners blocks: contiguous index ranges per rank (one file block per rank and field)
      // instead of METIS's parts, whose RVE indices interleave.
      if (a.get("owners", "metis") == "blocks")
        f.migrate_to(farm::partition_blocks(static_cast<std::size_t>(n), f.size()));
      common::StateStore mpm;
      mpm.write("solver/step", std::vector<std::int64_t>{1});
      double best = 1e300;
      for (int rep = 0; rep < 3; ++rep) {
        const double t0 = now();
        f.checkpoint(path, 1, 1e-3, "# bench_farm\n", mpm, false);
        best = std::min(best, now() - t0);
      }
      const auto bytes = static_cast<double>(std::filesystem::file_size(path));
      std::printf("checkpoint: ranks %d, %d %s RVEs\n", f.size(), n,
                  dem ? a.get("packing", MPMXDEM_DEFAULT_PACKING).c_str() : "tiny ElasticMicro");
      std::printf("  write (best of 3, incl. fsync + rename) %.4f s = %.3f ms per RVE\n", best,
                  1e3 * best / n);
      std::printf("  file size %.3f MB = %.1f B per RVE (chunked, shuffle + deflate 4)\n",
                  bytes / 1e6, bytes / n);
      f.stop();
    }
  }
  // Restart read: every rank reads the info, then its block of RVEs (collective).
  MPI_Barrier(comm);
  const double t0 = now();
  const farm::CheckpointInfo info = farm::read_checkpoint_info(path);
  const std::vector<int> owner = farm::partition_blocks(info.ids.size(), size_of(comm));
  std::vector<std::int64_t> mine;
  for (std::size_t k = 0; k < owner.size(); ++k)
    if (owner[k] == rank_of(comm)) mine.push_back(static_cast<std::int64_t>(k));
  const std::vector<common::StateStore> states = farm::read_checkpoint_rves(comm, info, mine);
  const double t_read = max_over_ranks(comm, now() - t0);
  if (rank_of(comm) == 0)
    std::printf("  read (info + collective RVE read, %zu states here) %.4f s = %.3f ms per RVE\n",
                states.size(), t_read, 1e3 * t_read / n);
}

// Rank 0's cost per MPM step of the farm's exchange with tiny RVEs (their own work ~0): the
// scatter of L, the gather of records and the bookkeeping, with --rves on a lattice (8 per cell).
// --migrate 1: then a migration to round-robin owners (time per moved RVE).
void exchange(const Args& a, MPI_Comm comm) {
  const int n = std::stoi(a.get("rves", "1000"));
  const int steps = std::stoi(a.get("steps", "50"));
  const Lattice lat = lattice(n);
  const std::vector<std::int64_t> ids = rve_ids(n);
  const double t_setup0 = now();
  farm::RveFarm f(comm, tiny_kind(), ids, lat.x, lat.grid, farm_options(a));
  const double t_setup = max_over_ranks(comm, now() - t_setup0);
  if (f.rank() != 0) {
    f.serve();
    return;
  }
  const int p = f.size();
  std::vector<Mat3> L(static_cast<std::size_t>(n), Mat3::Zero());
  for (std::size_t k = 0; k < L.size(); ++k) L[k](2, 2) = -1e-3 * (1.0 + 1e-4 * k);
  std::vector<Mat3> s(static_cast<std::size_t>(n));
  for (int k = 0; k < 3; ++k) f.update_stress(ids, L, 1e-6, s);  // warm-up
  // Per step: the wall of update_stress and its part outside the critical rank's RVE loop (the
  // exchange, rank 0's packing and unpacking, waiting); medians over the steps.
  std::vector<double> wall;
  std::vector<double> outside;
  for (int k = 0; k < steps; ++k) {
    const double c0 = f.times().critical_busy;
    const double w0 = now();
    f.update_stress(ids, L, 1e-6, s);
    wall.push_back(now() - w0);
    outside.push_back(wall.back() - (f.times().critical_busy - c0));
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  std::printf("exchange: ranks %d, %d tiny RVEs, %d steps (set-up incl. METIS %.4f s)\n", p, n,
              steps, t_setup);
  std::printf(
      "  bytes per step: scatter %lld (24 per rank + 72 per RVE), gather %lld (8 per "
      "rank + 160 per RVE)\n",
      24LL * p + 72LL * n, 8LL * p + 160LL * n);
  std::printf(
      "  per step (medians): update_stress wall %.1f us = %.4f us per RVE; outside the "
      "critical RVE loop %.1f us = %.4f us per RVE\n",
      1e6 * median(wall), 1e6 * median(wall) / n, 1e6 * median(outside), 1e6 * median(outside) / n);
  if (a.get("migrate", "0") == "1" && p > 1) {
    const std::vector<int> rr = farm::partition_round_robin(static_cast<std::size_t>(n), p);
    std::int64_t moved = 0;
    for (std::size_t k = 0; k < rr.size(); ++k) moved += rr[k] != f.owner()[k] ? 1 : 0;
    const double m0 = f.times().migrate_wall;
    f.migrate_to(rr);
    const double mw = f.times().migrate_wall - m0;
    std::printf("  migration to round-robin: %lld RVEs moved in %.4f s = %.2f us per moved RVE\n",
                static_cast<long long>(moved), mw, 1e6 * mw / std::max<std::int64_t>(moved, 1));
  }
  f.stop();
}

// Where a move's time goes, on this rank alone: one DEM RVE of the packing, stepped --steps times
// under the paper's strain rate (contacts with history), then saved, serialised, deserialised
// and loaded --reps times; the median of each phase and the state's size.
void move_phases(const Args& a, int steps) {
  const farm::MicroKind kind = dem_kind(a.get("packing", MPMXDEM_DEFAULT_PACKING));
  std::unique_ptr<farm::MicroModel> m = kind.create(0);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -2.5e-4 * std::sqrt(100e3 / 1600.0);
  for (int k = 0; k < steps; ++k) (void)m->step(l, 1.5e-3);
  const int reps = std::stoi(a.get("reps", "20"));
  std::map<std::string, std::vector<double>> t;
  std::size_t bytes = 0;
  for (int r = 0; r < reps; ++r) {
    double t0 = now();
    common::StateStore st;
    m->save(st);
    double t1 = now();
    const std::vector<char> blob = st.serialize();
    double t2 = now();
    const common::StateStore back = common::StateStore::deserialize(blob);
    double t3 = now();
    std::unique_ptr<farm::MicroModel> loaded = kind.load(back);
    double t4 = now();
    t["save"].push_back(t1 - t0);
    t["serialize"].push_back(t2 - t1);
    t["deserialize"].push_back(t3 - t2);
    t["load"].push_back(t4 - t3);
    bytes = blob.size();
  }
  std::printf("move phases (one RVE, %d reps, median): state %.0f kB;", reps, 1e-3 * double(bytes));
  {
    common::StateStore st;
    m->save(st);
    std::vector<std::pair<std::size_t, std::string>> sizes;
    for (const auto& [name, field] : st.fields())
      sizes.emplace_back(std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, field),
                         name);
    std::sort(sizes.rbegin(), sizes.rend());
    std::printf(" largest fields:");
    for (std::size_t i = 0; i < std::min<std::size_t>(sizes.size(), 6); ++i)
      std::printf(" %s %.0f kB,", sizes[i].second.c_str(), 1e-3 * double(sizes[i].first));
  }
  for (auto& [name, v] : t) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    std::printf(" %s %.3f ms", name.c_str(), 1e3 * v[v.size() / 2]);
  }
  std::printf("\n");
}

// What moving an RVE costs: 8 DEM RVEs of the reference packing under the paper's strain rate;
// after --steps steps every RVE changes rank (owner 1 - owner), then --steps more. Prints the
// migration's wall time per RVE and the moved RVEs' CPU time per step before and after the move
// (their first steps on the new rank pay for cold caches and rebuilt neighbour lists).
void move(const Args& a, MPI_Comm comm) {
  const int n = 8;
  const int steps = std::stoi(a.get("steps", "40"));
  const int size = size_of(comm);
  const std::vector<std::int64_t> ids = rve_ids(n);
  farm::RveFarm f = dem_farm_in_one_cell(a, comm, ids);
  if (f.rank() != 0) {
    f.serve();
    return;
  }
  std::vector<Mat3> L(static_cast<std::size_t>(n), Mat3::Zero());
  for (auto& l : L) l(2, 2) = -2.5e-4 * std::sqrt(100e3 / 1600.0);
  std::vector<Mat3> s(static_cast<std::size_t>(n));
  // Per-step CPU time of every RVE, summed over the RVEs: steps x total.
  auto run = [&](int count) {
    std::vector<double> per_step;
    std::vector<double> before = f.cost();
    for (int k = 0; k < count; ++k) {
      f.update_stress(ids, L, 1.5e-3, s);
      const std::vector<double> c = f.cost();
      double sum = 0.0;
      for (std::size_t j = 0; j < c.size(); ++j) sum += c[j] - before[j];
      per_step.push_back(sum / n);
      before = c;
    }
    return per_step;
  };
  const std::vector<double> warm = run(steps);
  std::vector<int> owner = f.owner();
  for (int& o : owner) o = (o + 1) % size;
  const double m0 = f.times().migrate_wall;
  f.migrate_to(owner);
  const double migrate = f.times().migrate_wall - m0;
  const std::vector<double> after = run(steps);
  const double steady = std::accumulate(warm.end() - steps / 2, warm.end(), 0.0) / (steps / 2);
  double excess = 0.0;
  for (const double c : after) excess += c - steady;
  std::printf("move: %d DEM RVEs on %d ranks, every RVE moved after %d steps\n", n, size, steps);
  std::printf("  migration wall %.2f ms per RVE\n", 1e3 * migrate / n);
  std::printf("  CPU per RVE and step: steady %.3f ms; after the move:", 1e3 * steady);
  for (int k = 0; k < std::min(steps, 6); ++k)
    std::printf(" %.3f", 1e3 * after[static_cast<std::size_t>(k)]);
  std::printf(" ms ...\n  excess over the %d steps after the move: %.2f ms per RVE\n", steps,
              1e3 * excess);
  f.stop();
  move_phases(a, steps);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  Args a;
  if (argc > 1) a.mode = argv[1];
  for (int i = 2; i + 1 < argc; i += 2) {
    std::string k = argv[i];
    if (k.rfind("--", 0) == 0) k = k.substr(2);
    a.opt[k] = argv[i + 1];
  }
  int rc = 0;
  try {
    if (a.mode == "overhead") {
      overhead(a, MPI_COMM_WORLD);
    } else if (a.mode == "balance") {
      balance(a, MPI_COMM_WORLD);
    } else if (a.mode == "checkpoint") {
      checkpoint(a, MPI_COMM_WORLD);
    } else if (a.mode == "move") {
      move(a, MPI_COMM_WORLD);
    } else if (a.mode == "exchange") {
      exchange(a, MPI_COMM_WORLD);
    } else if (a.mode == "partition") {
      if (rank_of(MPI_COMM_WORLD) == 0) bench_farm::partition(a);
    } else {
      std::fprintf(
          stderr,
          "usage: bench_farm overhead|balance|checkpoint|move|exchange|partition [--option value "
          "...]\n");
      rc = 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_farm: %s\n", e.what());
    rc = 1;
  }
  MPI_Finalize();
  return rc;
}
