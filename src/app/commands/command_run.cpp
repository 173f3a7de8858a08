// `mpmxdem run JOB` (a coupled MPM x DEM run through the RVE farm, or its restart); `mpmxdem
// inspect` is in command_inspect.cpp.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <set>

#include "app/commands/commands.hpp"
#include "app/job/memory_check.hpp"
#include "app/run/restart_check.hpp"
#include "app/run/restart_latest.hpp"
#include "app/run/run_summary.hpp"
#include "app/run/stop_signals.hpp"
#include "app/run/wall_budget.hpp"
#include "app/setup/coupled_setup.hpp"
#include "app/setup/mpm_setup.hpp"
#include "common/errors.hpp"
#include "farm/driver.hpp"
#include "farm/mpi_util.hpp"
#include "farm/partition.hpp"
#include "farm/run_schedules.hpp"

namespace app {
namespace {

// --restart latest: resolved once, on rank 0, so that every rank continues from the same file.
void resolve_restart_latest(Options& o, const Comm& comm) {
  if (o.restart != kRestartLatest) return;
  on_root(comm, [&] { o.restart = latest_checkpoint(output_path(o)); });
  farm::bcast_string(comm.comm, o.restart);
  spdlog::info("--restart latest: {}", o.restart.empty()
                                           ? "no checkpoint in " + output_path(o).string() +
                                                 " yet: starting from the beginning"
                                           : "continuing from " + o.restart);
}

// OpenMP threads per rank (the node's cores over its ranks) unless OMP_NUM_THREADS says.
void set_threads(const Comm& comm) {
  const int threads = farm::threads_per_rank(comm.comm);
  if (std::getenv("OMP_NUM_THREADS") == nullptr) {
    omp_set_num_threads(threads);
    spdlog::info("OpenMP: {} thread(s) per rank ({} rank(s)); set OMP_NUM_THREADS to choose",
                 threads, comm.size);
  } else {
    spdlog::info("OpenMP: OMP_NUM_THREADS = {} (this node's cores per rank: {})",
                 std::getenv("OMP_NUM_THREADS"), threads);
  }
}

// The points by ascending id and the rank that starts with each (farm::Placement's contiguous
// blocks; farm.rank0_rves = false leaves rank 0 to the MPM).
struct StartPlacement {
  std::vector<std::size_t> by_id;  ///< point indices by ascending id
  std::vector<int> rank;           ///< rank of by_id[k]
  [[nodiscard]] bool mine(std::size_t k, int me) const { return rank[k] == me; }
};

StartPlacement start_placement(const MpmSetup& setup, const farm::CoupledConfig& cfg,
                               const Comm& comm) {
  StartPlacement p;
  p.by_id.resize(setup.points.size());
  for (std::size_t i = 0; i < p.by_id.size(); ++i) p.by_id[i] = i;
  std::sort(p.by_id.begin(), p.by_id.end(),
            [&](std::size_t a, std::size_t b) { return setup.points.id[a] < setup.points.id[b]; });
  const int first_worker = !cfg.farm.rank0_rves && comm.size > 1 ? 1 : 0;
  p.rank = farm::partition_blocks(p.by_id.size(), comm.size - first_worker);
  for (int& r : p.rank) r += first_worker;
  return p;
}

// The DEM RVEs against the memory of the nodes, before any preparation (docs/reference/errors.md).
void check_memory(const Job& job, const MpmSetup& setup, const StartPlacement& place,
                  std::int64_t spheres, const Comm& comm) {
  agree(comm, [&] {
    RveMemory m;
    m.spheres = spheres;
    std::vector<std::int64_t> per_body(job.count("mpm.body"), 0);
    for (std::size_t k = 0; k < place.by_id.size(); ++k) {
      const std::size_t i = place.by_id[k];
      if (setup.points.material[i] != kDemMaterial) continue;
      ++m.rves;
      ++per_body[static_cast<std::size_t>(setup.body[i])];
      if (place.mine(k, comm.rank)) ++m.held;
    }
    if (m.rves == 0) return;
    const auto biggest = std::max_element(per_body.begin(), per_body.end()) - per_body.begin();
    m.key = fmt::format("mpm.body[{}].points_per_cell", biggest);
    check_rve_memory(job, m, comm);
  });
}

// A damaged checkpoint, or one of another job, is refused before anything is written; so is an
// end time beyond reach (it may change at a restart), from the mean dt so far. Returns the
// checkpoint's RVE count.
std::size_t check_restart_file(const Job& job, const Options& o, const farm::CoupledConfig& cfg,
                               const Comm& comm) {
  std::size_t rves = cfg.points.size();
  on_root(comm, [&] {
    const farm::CheckpointInfo info = farm::inspect_checkpoint(o.restart, true);
    check_restart(job, o.restart, info.job_text, output_path(o));
    rves = info.ids.size();
    if (info.step > 0 && info.time > 0.0 && cfg.end_time > info.time) {
      check_step_count(job, o,
                       (cfg.end_time - info.time) / (info.time / static_cast<double>(info.step)),
                       "MPM", "mpm.end_time");
    }
  });
  return rves;
}

// The micro models are prepared now, not on the farm's first use: a DEM sample that cannot be
// prepared fails before anything is written. Every preparation the job needs is made here, once,
// spread over the ranks and their threads (MicroKind::prepare), each rank asking for the points
// the farm will create on it first (its start-up blocks of the ascending ids) and for one point of
// each material (the wave-speed checks). The farm's RVEs are copies of what this made (the micro
// kind keeps it) and its own prepare call finds it there, so nothing is prepared twice. Returns
// the largest wave speed of the materials [m/s].
double prepare_micro_models(const MpmSetup& setup, const farm::CoupledConfig& cfg,
                            const StartPlacement& place, const Comm& comm) {
  std::vector<std::int64_t> first;  // one point of each material, in point order
  std::vector<std::int64_t> ask;    // this rank's start-up block, and `first`
  std::set<std::int32_t> materials;
  for (std::size_t i = 0; i < setup.points.size(); ++i)
    if (materials.insert(setup.points.material[i]).second) first.push_back(setup.points.id[i]);
  for (std::size_t k = 0; k < place.by_id.size(); ++k)
    if (place.mine(k, comm.rank)) ask.push_back(setup.points.id[place.by_id[k]]);
  ask.insert(ask.end(), first.begin(), first.end());
  if (cfg.micro.prepare) agree(comm, [&] { cfg.micro.prepare(ask, comm.comm); });
  double wave_speed = 0.0;
  agree(comm, [&] {
    for (const std::int64_t id : first) {
      const auto micro = cfg.micro.create(id);
      const common::Mat3 stress = micro->stress();
      if (!stress.allFinite() || !std::isfinite(micro->wave_speed())) {
        throw common::NumericalError(fmt::format(
            "the micro model of point id {} starts with a non-finite stress (trace {}) or wave "
            "speed ({} m/s): its sample cannot be prepared (a degenerate packing?)",
            id, stress.trace(), micro->wave_speed()));
      }
      wave_speed = std::max(wave_speed, micro->wave_speed());
    }
  });
  return wave_speed;
}

// The job's boundary velocities, step count and fixed dt against the materials' wave speed.
void check_wave_speed_limits(const Job& job, const Options& o, const farm::CoupledConfig& cfg,
                             double wave_speed) {
  const double h = cfg.solver.grid.spacing.minCoeff();
  // Mass scaling s: the inertia is s m, the wave speed c / sqrt(s) (mpm::Solver::stable_dt).
  const double s = cfg.solver.mass_scaling;
  const double c = s != 1.0 ? wave_speed / std::sqrt(s) : wave_speed;
  // A boundary driven faster than the material's wave speed is a shock the explicit step cannot
  // follow (its first step moves the boundary nodes by more than a cell): refused by key.
  for (std::size_t k = 0; k < job.count("mpm.velocity"); ++k) {
    for (const char* axis : {"x", "y", "z"}) {
      const std::string key = fmt::format("mpm.velocity[{}].{}", k, axis);
      if (!job.has(key) || !(std::abs(job.number(key)) >= c)) continue;
      throw common::InputError(job.message(
          key, fmt::format("|v| = {:.4g} m/s is not below the largest wave speed of the "
                           "materials, c = {:.4g} m/s{}: the boundary would outrun the waves "
                           "it sends into the material (a shock the explicit step cannot "
                           "follow); velocity in m/s?",
                           std::abs(job.number(key)), c,
                           s != 1.0 ? fmt::format(" (with mpm.mass_scaling = {:.6g})", s)
                                    : std::string())));
    }
  }
  // At least end_time / dt steps: the CFL step only shrinks as the points move.
  if (c > 0.0) {
    const double dt = job.has("mpm.dt") ? job.number("mpm.dt") : cfg.solver.cfl * h / c;
    check_step_count(job, o, cfg.end_time / dt, "MPM", "mpm.end_time");
  }
  if (job.has("mpm.dt") && c > 0.0 && job.number("mpm.dt") > h / c) {
    throw common::InputError(job.message(
        "mpm.dt",
        fmt::format("above the stability limit h / c = {:.4g} s (smallest spacing h = "
                    "{:.4g} m, largest wave speed of the materials c = {:.4g} m/s{}): "
                    "the explicit step would blow up; lower it, or leave dt out to "
                    "use the CFL step",
                    h / c, h, c,
                    s != 1.0 ? fmt::format(" with mpm.mass_scaling = {:.6g}: {:.4g} / sqrt({:.6g})",
                                           s, wave_speed, s)
                             : std::string())));
  }
}

// From the start of the run a signal (a batch system's warning or time limit, Ctrl-C) or the
// --max-wall budget ends the run after the current MPM step, with a checkpoint.
std::function<int()> stop_request(std::optional<WallBudget>& budget) {
  return [&budget, said = false]() mutable {
    int why = StopSignals::received();
    if (why == 0 && budget && budget->spent(WallBudget::Clock::now())) why = kStopWallBudget;
    if (why != 0 && !said) {
      said = true;
      spdlog::warn("{}: the run ends after this MPM step, with a checkpoint",
                   why == kStopWallBudget
                       ? fmt::format("--max-wall {}: too little wall time left for another step",
                                     farm::format_duration(budget->seconds()))
                       : signal_name(why) + " received");
    }
    return why;
  };
}

// Rank 0's closing lines: work, balance, outputs, and how to continue a stopped run.
void log_summary(const farm::RunSummary& s, const Options& given, const std::filesystem::path& out,
                 const std::optional<WallBudget>& budget) {
  const double busy = run_balance(s);
  spdlog::info(
      "done: {} MPM steps, t = {:.6g} s, wall {:.2f} s; RVE time {:.2f} s of the critical rank, "
      "balance (mean/max busy) {:.3f}, {} migration(s) moving {} RVE(s) in {:.2f} s; {} "
      "checkpoint(s) written{}",
      s.steps, s.time, s.wall_s, s.times.critical_busy, busy, s.migrations, s.rves_moved,
      s.times.migrate_wall, s.checkpoints.size(),
      s.checkpoints.empty() ? "" : ", last " + s.checkpoints.back());
  spdlog::info(
      "work: {} DEM steps in {} RVE steps of this run ({:.3g} per RVE step); {} RVE "
      "step(s) spared ({:.3g} %, dem.sparing)",
      s.dem_steps, s.rve_steps,
      s.rve_steps > 0 ? static_cast<double>(s.dem_steps) / static_cast<double>(s.rve_steps) : 0.0,
      s.spared_steps,
      s.rve_steps > 0
          ? 100.0 * static_cast<double>(s.spared_steps) / static_cast<double>(s.rve_steps)
          : 0.0);
  spdlog::info("results: {0}/results.h5 (time series), {0}/points.xmf (ParaView), {0}/means.csv",
               out.string());
  if (s.stopped_by != 0) {
    const bool wall = s.stopped_by == kStopWallBudget;
    spdlog::warn(
        "stopped by {} at step {}, t = {:.6g} s, before the end{}; continue with `mpmxdem run "
        "{} --out {} --restart latest` (exit {})",
        wall ? "--max-wall " + farm::format_duration(budget->seconds()) : signal_name(s.stopped_by),
        s.steps, s.time, s.checkpoints.empty() ? "" : ": checkpoint " + s.checkpoints.back(),
        given.job, out.string(),
        wall ? std::to_string(kExitWallBudget)
             : fmt::format("{} = 128 + {}", 128 + s.stopped_by, s.stopped_by));
  }
}

}  // namespace

// The order matters: everything the job implies (output directory, packing, mapping, memory,
// checkpoint, preparations, stability) is checked before the output directory is touched.
int command_run(const Options& given, const Comm& comm) {
  const auto started = WallBudget::Clock::now();  // --max-wall counts from here
  const Job job = load_job_collective(given.job, comm);
  check_omp_environment(comm);
  Options o = given;
  resolve_restart_latest(o, comm);
  if (!job.has_section("mpm")) {
    throw common::InputError(fmt::format(
        "{}: `run` needs an [mpm] section (a pure DEM job runs with `mpmxdem dem`)", job.file()));
  }
  set_threads(comm);  // first: the sample preparation below runs with them
  check_output(o, comm);
  const std::int64_t spheres = check_job_packing(job, comm);
  std::optional<farm::CoupledConfig> config;
  std::optional<MpmSetup> setup;
  agree(comm, [&] {
    setup.emplace(mpm_setup(job));
    config.emplace(coupled_setup(job, *setup, RunLimits{output_path(o).string(), o.max_steps}));
  });
  const farm::CoupledConfig& cfg = *config;
  const StartPlacement place = start_placement(*setup, cfg, comm);
  check_memory(job, *setup, place, spheres, comm);
  std::size_t rves = cfg.points.size();
  if (!o.restart.empty()) {
    rves = check_restart_file(job, o, cfg, comm);
  } else {
    check_wave_speed_limits(job, o, cfg, prepare_micro_models(*setup, cfg, place, comm));
  }
  const std::filesystem::path out = open_output(o, job, comm);
  // The ranks that may own RVEs (farm.rank0_rves = false leaves rank 0 to the MPM).
  const auto workers =
      static_cast<std::size_t>(!cfg.farm.rank0_rves && comm.size > 1 ? comm.size - 1 : comm.size);
  if (comm.rank == 0 && workers > rves) {
    spdlog::warn("{} ranks for {} RVE(s): {} rank(s) will hold no RVE and only wait", comm.size,
                 rves, workers - rves);
  }
  spdlog::info(
      "coupled run: {} material points, end time {:.6g} s{}", cfg.points.size(), cfg.end_time,
      cfg.max_steps > 0 ? fmt::format(", at most {} MPM steps in total", cfg.max_steps) : "");
  // From here a signal ends the run after the current MPM step with a checkpoint, instead of
  // killing it (docs/reference/errors.md).
  const StopSignals signals;
  std::optional<WallBudget> budget;
  if (o.max_wall_s > 0.0) budget.emplace(o.max_wall_s, started);
  config->stop_requested = stop_request(budget);
  RunRecord record;
  record.job = given.job;
  record.restart = o.restart;
  record.ranks = comm.size;
  record.threads = omp_get_max_threads();
  record.end_time = cfg.end_time;
  record.max_steps = cfg.max_steps;
  try {
    record.summary = o.restart.empty() ? farm::run_coupled(cfg, comm.comm)
                                       : farm::restart_coupled(cfg, o.restart, comm.comm);
  } catch (const common::NumericalError& e) {
    // Every rank throws the same failure (the farm's error agreement): rank 0 records it, and a
    // record it cannot store does not hide the failure.
    if (comm.rank == 0) {
      record.exit_code = 3;
      record.error = e.what();
      try {
        write_run_summary(out, record);
      } catch (const common::IoError& io) {
        spdlog::warn("{} not written: {}", kRunSummaryFile, io.what());
      }
    }
    throw;
  }
  const farm::RunSummary& s = *record.summary;
  if (comm.rank == 0) log_summary(s, given, out, budget);
  record.exit_code = s.stopped_by == kStopWallBudget ? kExitWallBudget
                     : s.stopped_by != 0             ? 128 + s.stopped_by
                                                     : 0;
  on_root(comm, [&] { write_run_summary(out, record); });  // an I/O failure: every rank's exit 4
  return record.exit_code;
}

}  // namespace app
