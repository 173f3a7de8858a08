// The subcommands of mpmxdem. Each runs on every MPI rank (collective), returns the exit code,
// and throws common::InputError for bad input (the same on every rank).
#pragma once

#include <mpi.h>

#include <filesystem>
#include <functional>

#include "app/commands/cli.hpp"
#include "app/job/job.hpp"

namespace app {

struct Comm {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0;
  int size = 1;
};

/// Collective: runs `f` on every rank; an exception on any rank becomes the same exception (type
/// and message of the lowest failing rank) on every rank, so no rank is left waiting in a later
/// collective. Use it for every step before the farm's collective phase that can fail.
void agree(const Comm& comm, const std::function<void()>& f);
/// Collective: runs `f` on rank 0 only; its exception is thrown on every rank (as agree()).
void on_root(const Comm& comm, const std::function<void()>& f);

/// Rank 0 reads the job file and broadcasts its text; every rank parses and validates it, so an
/// error is seen (and thrown) on every rank alike.
[[nodiscard]] Job load_job_collective(const std::string& path, const Comm& comm);

/// The output directory of a command: --out, or results/<job file name>.
[[nodiscard]] std::filesystem::path output_path(const Options& o);

/// Collective: checks, without writing anything, that the output directory may receive this
/// command's output (see check_output_dir). Call it before any long set-up.
void check_output(const Options& o, const Comm& comm);

/// Collective: checks the output directory again, then (rank 0) creates it, locks it (lock file
/// mpmxdem.lock naming the holder: a second run into it is refused), and writes the job, the
/// resolved job and the log file there. Call it only once everything that can be checked has been
/// checked: nothing is written before it. An error on rank 0 is thrown on every rank. Returns the
/// directory.
std::filesystem::path open_output(const Options& o, const Job& job, const Comm& comm);

/// Collective: the packing of the job's [dem.sample] (when it has one), read and checked on rank 0
/// (read_packing, check_packing; a generated sample: its memory bound). Throws the InputError
/// naming the packing file and line on every rank. Returns, on every rank, the spheres of one
/// sample (the packing's, or dem.sample.spheres of a generated one); 0 without [dem.sample].
std::int64_t check_job_packing(const Job& job, const Comm& comm);

/// A run that implies more than 1e12 steps (years of computing: an end time of 1e300 s, an
/// inertial number of 1e-30, a unit slip) is refused naming `key` (`what`: "DEM" or "MPM" steps),
/// unless --max-steps bounds it: it would run for ever, writing its outputs.
void check_step_count(const Job& job, const Options& o, double steps, const std::string& what,
                      const std::string& key);

/// Collective: OMP_NUM_THREADS, when set, must be a thread count >= 1 (or a comma-separated list
/// of them, one per nesting level) and at most kMaxThreadsPerCore per core this rank may use;
/// otherwise an InputError naming the variable, its value and the rule on every rank (libgomp
/// would ignore a bad value and use every core; 10^5 threads crashed the run).
void check_omp_environment(const Comm& comm);
inline constexpr int kMaxThreadsPerCore = 64;

int command_check(const Options& o, const Comm& comm);
int command_run(const Options& o, const Comm& comm);
int command_schema(const Options& o, const Comm& comm);
int command_dem(const Options& o, const Comm& comm);
int command_bench(const Options& o, const Comm& comm);
int command_inspect(const Options& o, const Comm& comm);

}  // namespace app
