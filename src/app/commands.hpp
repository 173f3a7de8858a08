// The subcommands of mpmxdem. Each runs on every MPI rank (collective), returns the exit code,
// and throws common::InputError for bad input (the same on every rank).
#pragma once

#include <mpi.h>

#include <filesystem>

#include "app/cli.hpp"
#include "app/job.hpp"

namespace app {

struct Comm {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0;
  int size = 1;
};

/// Broadcasts rank 0's error text; when it is not empty, every rank throws it as an InputError.
void bcast_error(std::string& error, const Comm& comm);

/// Rank 0 reads the job file and broadcasts its text; every rank parses and validates it, so an
/// error is seen (and thrown) on every rank alike.
[[nodiscard]] Job load_job_collective(const std::string& path, const Comm& comm);

/// The output directory of a command: --out, or results/<job file name>.
[[nodiscard]] std::filesystem::path output_path(const Options& o);

/// Checks the output directory on every rank, then (rank 0) creates it and writes the job, the
/// resolved job and the log file there. Returns the directory.
std::filesystem::path open_output(const Options& o, const Job& job, const Comm& comm);

int command_check(const Options& o, const Comm& comm);
int command_run(const Options& o, const Comm& comm);
int command_schema(const Options& o, const Comm& comm);
int command_dem(const Options& o, const Comm& comm);
int command_bench(const Options& o, const Comm& comm);
int command_inspect(const Options& o, const Comm& comm);

}  // namespace app
