// check and schema subcommands, and what every command shares (job loading, output directory): see
// commands.hpp.
#include "app/commands/commands.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <omp.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "app/commands/version.hpp"
#include "app/job/memory_check.hpp"
#include "app/run/logging.hpp"
#include "app/run/output_dir.hpp"
#include "app/setup/coupled_setup.hpp"
#include "app/setup/dem_setup.hpp"
#include "app/setup/mpm_setup.hpp"
#include "common/errors.hpp"
#include "dem/packing_io.hpp"
#include "farm/mpi_util.hpp"
#include "farm/results.hpp"

namespace app {

void agree(const Comm& comm, const std::function<void()>& f) {
  farm::ErrorKind kind = farm::ErrorKind::none;
  std::string message;
  try {
    f();
  } catch (const std::exception& e) {
    kind = farm::current_error_kind();
    message = e.what();
  }
  farm::agree_on_errors(comm.comm, kind, message);
}

void on_root(const Comm& comm, const std::function<void()>& f) {
  farm::ErrorKind kind = farm::ErrorKind::none;
  std::string message;
  if (comm.rank == 0) {
    try {
      f();
    } catch (const std::exception& e) {
      kind = farm::current_error_kind();
      message = e.what();
    }
  }
  // The other ranks wait without holding a core (f may be a long preparation on rank 0).
  MPI_Request barrier = MPI_REQUEST_NULL;
  MPI_Ibarrier(comm.comm, &barrier);
  farm::wait_for(barrier, farm::WaitMode::sleep);
  farm::agree_on_errors(comm.comm, kind, message);
}

Job load_job_collective(const std::string& path, const Comm& comm) {
  std::string text;
  // Job::load checks existence and readability with the message users see.
  on_root(comm, [&] { text = Job::load(path).source_text(); });
  farm::bcast_string(comm.comm, text);
  std::optional<Job> job;
  agree(comm, [&] { job.emplace(Job::parse(text, path)); });
  return std::move(*job);
}

std::int64_t check_job_packing(const Job& job, const Comm& comm) {
  if (!job.has_section("dem.sample")) return 0;
  std::int64_t spheres = job.has("dem.sample.spheres") ? job.integer("dem.sample.spheres") : 0;
  on_root(comm, [&] {
    if (job.has("dem.sample.packing")) {
      bool generated = false;
      const dem::Packing pk = dem_packing(job, generated);  // read_packing checks it
      spheres = static_cast<std::int64_t>(pk.r.size());
      // The neighbour search needs every cell width >= 2 r_max + skin.
      const double r_max = *std::max_element(pk.r.begin(), pk.r.end());
      const double skin = job.number("dem.numerics.verlet_skin") * r_max;
      for (int a = 0; a < 3; ++a) {
        if (pk.cell.width(a) < 2.0 * r_max + skin) {
          throw common::InputError(job.message(
              "dem.sample.packing",
              fmt::format("the cell of this packing is {:.6g} m wide across axis {}, below 2 r_max "
                          "+ skin = {:.6g} m (r_max {:.6g} m, dem.numerics.verlet_skin {}): too "
                          "few spheres across the cell for a periodic simulation",
                          pk.cell.width(a), a, 2.0 * r_max + skin, r_max,
                          job.number("dem.numerics.verlet_skin"))));
        }
      }
    }
  });
  MPI_Bcast(&spheres, 1, MPI_INT64_T, 0, comm.comm);
  return spheres;
}

void check_step_count(const Job& job, const Options& o, double steps, const std::string& what,
                      const std::string& key) {
  constexpr double kMaxSteps = 1e12;
  if (o.max_steps >= 0 || steps <= kMaxSteps) return;
  throw common::InputError(job.message(
      key, fmt::format("implies about {:.3g} {} steps, more than {:.0e} (years of computing): "
                       "shorten the run, or bound it with --max-steps",
                       steps, what, kMaxSteps)));
}

void check_omp_environment(const Comm& comm) {
  agree(comm, [] {
    const char* env = std::getenv("OMP_NUM_THREADS");
    if (env == nullptr) return;
    const std::string text = env;
    // Empty (a script's `OMP_NUM_THREADS=$UNSET`): as unset, OpenMP's default.
    if (text.find_first_not_of(" \t") == std::string::npos) return;
    const std::string shown = text.size() > 60 ? text.substr(0, 57) + "..." : text;
    std::int64_t first = 0;
    std::size_t at = 0;
    do {
      const std::size_t comma = std::min(text.find(',', at), text.size());
      std::string item = text.substr(at, comma - at);
      item.erase(0, item.find_first_not_of(" \t"));
      item.erase(item.find_last_not_of(" \t") + 1);
      std::int64_t v = 0;
      const auto r = std::from_chars(item.data(), item.data() + item.size(), v);
      if (item.empty() || r.ec != std::errc() || r.ptr != item.data() + item.size() || v < 1) {
        throw common::InputError(fmt::format(
            "OMP_NUM_THREADS (environment) = '{}': must be a thread count >= 1 (or a "
            "comma-separated list of them, one per nesting level); OpenMP would ignore it and use "
            "every core",
            shown));
      }
      if (at == 0) first = v;
      at = comma + 1;
    } while (at <= text.size());
    const int cores = std::max(1, omp_get_num_procs());
    if (first > static_cast<std::int64_t>(kMaxThreadsPerCore) * cores) {
      throw common::InputError(fmt::format(
          "OMP_NUM_THREADS (environment) = {}: more than {} threads per core of the {} core(s) "
          "this rank may use (at most {}): a typo? one thread per core is the fastest",
          shown, kMaxThreadsPerCore, cores, kMaxThreadsPerCore * cores));
    }
  });
}

int command_check(const Options& o, const Comm& comm) {
  const Job job = load_job_collective(o.job, comm);
  const std::int64_t spheres = check_job_packing(job, comm);
  std::int64_t dem_points = 0;
  if (job.has_section("mpm")) {
    // The mapping onto the grid and the run set-up: the errors `run` would give before writing.
    agree(comm, [&] {
      const MpmSetup setup = mpm_setup(job);
      (void)coupled_setup(job, setup, RunLimits{"(check)", -1});
      dem_points =
          std::count(setup.points.material.begin(), setup.points.material.end(), kDemMaterial);
    });
  }
  if (comm.rank == 0 && dem_points > 0) {
    // What a run will need: `run` refuses a start where the RVEs of a node exceed its memory.
    spdlog::info(
        "{} DEM RVEs of {} spheres: at least {} of memory in all ({:.0f} bytes per sphere; a run's "
        "peak is about twice that), spread over the nodes of the run",
        dem_points, spheres,
        format_bytes(static_cast<double>(dem_points) * static_cast<double>(spheres) *
                     kRveBytesPerSphere),
        kRveBytesPerSphere);
  }
  if (comm.rank == 0) {
    std::fputs(job.resolved_toml().c_str(), stdout);
    spdlog::info("{}: valid", o.job);
  }
  return 0;
}

int command_schema(const Options& o, const Comm& comm) {
  if (comm.rank == 0) {
    const std::string text =
        o.schema_outputs ? farm::results_reference_markdown() : schema_markdown(job_schema());
    std::fputs(text.c_str(), stdout);
  }
  return 0;
}

std::filesystem::path output_path(const Options& o) {
  return o.out.empty() ? default_output_dir(o.job) : std::filesystem::path(o.out);
}

void check_output(const Options& o, const Comm& comm) {
  agree(comm, [&] { check_output_dir(output_path(o), o.force, !o.restart.empty()); });
}

std::filesystem::path open_output(const Options& o, const Job& job, const Comm& comm) {
  const std::filesystem::path out = output_path(o);
  check_output(o, comm);  // every rank has checked before anything is written
  on_root(comm, [&] {
    create_output_dir(out);
    try {
      lock_output_dir(out);
      try {
        add_log_file((out / "log.txt").string());
      } catch (const std::exception& e) {
        throw common::InputError(fmt::format("cannot write the log file '{}': {}",
                                             (out / "log.txt").string(), e.what()));
      }
      write_file_atomic(out / "job.toml", job.source_text());
      write_file_atomic(out / "job.resolved.toml", job.resolved_toml());
    } catch (const common::IoError& e) {
      // The storage failed before the run began (a full disk, a quota): exit 4, and nothing of
      // the run is left, as for a run refused (main takes back what an input error leaves).
      remove_log_file();
      const std::string undone = discard_refused_output();
      throw common::IoError(std::string(e.what()) +
                            (undone.empty() ? std::string() : "\nnothing written: " + undone));
    }
  });
  spdlog::info("mpmxdem {} `{}` on {} rank(s); job {}; output {}", kVersion, o.command, comm.size,
               o.job, out.string());
  spdlog::info("resolved job:\n{}", job.resolved_toml());
  return out;
}

}  // namespace app
