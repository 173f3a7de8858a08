// `mpmxdem run JOB` (a coupled MPM x DEM run through the RVE farm, or its restart) and
// `mpmxdem inspect CKPT` (what a checkpoint holds).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <omp.h>

#include <cstdio>
#include <cstdlib>

#include "app/commands.hpp"
#include "app/coupled_setup.hpp"
#include "common/errors.hpp"
#include "farm/driver.hpp"
#include "farm/mpi_util.hpp"

namespace app {

int command_run(const Options& o, const Comm& comm) {
  const Job job = load_job_collective(o.job, comm);
  if (!job.has_section("mpm")) {
    throw common::InputError(fmt::format(
        "{}: `run` needs an [mpm] section (a pure DEM job runs with `mpmxdem dem`)", job.file()));
  }
  // Everything the job implies is checked before the output directory is touched.
  const farm::CoupledConfig cfg =
      coupled_setup(job, RunLimits{output_path(o).string(), o.max_steps});
  if (!o.restart.empty()) {
    // A damaged checkpoint is refused before anything is written (collective: same error
    // everywhere).
    std::string error;
    if (comm.rank == 0) {
      try {
        const farm::CheckpointInfo info = farm::inspect_checkpoint(o.restart, true);
        if (info.job_text != job.source_text()) {
          spdlog::warn(
              "{}: the job file differs from the one the checkpoint was written with; its grid, "
              "loads, "
              "end and outputs are used, the state comes from the checkpoint",
              o.job);
        }
      } catch (const common::InputError& e) {
        error = e.what();
      }
    }
    bcast_error(error, comm);
  }
  const std::filesystem::path out = open_output(o, job, comm);
  const int threads = farm::threads_per_rank(comm.comm);
  if (std::getenv("OMP_NUM_THREADS") == nullptr) {
    omp_set_num_threads(threads);
    spdlog::info("OpenMP: {} thread(s) per rank ({} rank(s)); set OMP_NUM_THREADS to choose",
                 threads, comm.size);
  } else {
    spdlog::info("OpenMP: OMP_NUM_THREADS = {} (this node's cores per rank: {})",
                 std::getenv("OMP_NUM_THREADS"), threads);
  }
  spdlog::info(
      "coupled run: {} material points, end time {:.6g} s{}", cfg.points.size(), cfg.end_time,
      cfg.max_steps > 0 ? fmt::format(", at most {} MPM steps in total", cfg.max_steps) : "");
  const farm::RunSummary s = o.restart.empty() ? farm::run_coupled(cfg, comm.comm)
                                               : farm::restart_coupled(cfg, o.restart, comm.comm);
  if (comm.rank == 0) {
    const double busy =
        s.times.critical_busy > 0.0 ? s.times.mean_busy / s.times.critical_busy : 1.0;
    spdlog::info(
        "done: {} MPM steps, t = {:.6g} s, wall {:.1f} s; RVE time {:.1f} s of the critical rank, "
        "balance (mean/max busy) {:.3f}, {} migration(s) moving {} RVE(s) in {:.2f} s; {} "
        "checkpoint(s) written{}",
        s.steps, s.time, s.wall_s, s.times.critical_busy, busy, s.migrations, s.rves_moved,
        s.times.migrate_wall, s.checkpoints.size(),
        s.checkpoints.empty() ? "" : ", last " + s.checkpoints.back());
    spdlog::info("results: {0}/results.h5 (time series), {0}/points.xmf (ParaView), {0}/means.csv",
                 out.string());
  }
  return 0;
}

int command_inspect(const Options& o, const Comm& comm) {
  if (comm.rank != 0) return 0;
  std::fputs(farm::describe(farm::inspect_checkpoint(o.job, true)).c_str(), stdout);
  return 0;
}

}  // namespace app
