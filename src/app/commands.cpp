// check and schema subcommands, and what every command shares (job loading, output directory): see
// commands.hpp.
#include "app/commands.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "app/logging.hpp"
#include "app/output_dir.hpp"
#include "app/version.hpp"
#include "common/errors.hpp"
#include "farm/mpi_util.hpp"

namespace app {

void bcast_error(std::string& error, const Comm& comm) {
  farm::bcast_string(comm.comm, error);
  if (!error.empty()) throw common::InputError(error);
}

Job load_job_collective(const std::string& path, const Comm& comm) {
  std::string text;
  std::string error;
  if (comm.rank == 0) {
    try {
      // Job::load checks existence and readability with the message users see.
      text = Job::load(path).source_text();
    } catch (const common::InputError& e) {
      error = e.what();
    }
  }
  bcast_error(error, comm);
  farm::bcast_string(comm.comm, text);
  return Job::parse(text, path);
}

int command_check(const Options& o, const Comm& comm) {
  const Job job = load_job_collective(o.job, comm);
  if (comm.rank == 0) {
    std::fputs(job.resolved_toml().c_str(), stdout);
    spdlog::info("{}: valid", o.job);
  }
  return 0;
}

int command_schema(const Options& /*o*/, const Comm& comm) {
  if (comm.rank == 0) std::fputs(schema_markdown(job_schema()).c_str(), stdout);
  return 0;
}

std::filesystem::path output_path(const Options& o) {
  return o.out.empty() ? default_output_dir(o.job) : std::filesystem::path(o.out);
}

std::filesystem::path open_output(const Options& o, const Job& job, const Comm& comm) {
  const std::filesystem::path out = output_path(o);
  check_output_dir(out, o.force, !o.restart.empty());
  MPI_Barrier(comm.comm);  // every rank has checked before anything is written
  if (comm.rank == 0) {
    create_output_dir(out);
    add_log_file((out / "log.txt").string());
    write_file_atomic(out / "job.toml", job.source_text());
    write_file_atomic(out / "job.resolved.toml", job.resolved_toml());
  }
  spdlog::info("mpmxdem {} `{}` on {} rank(s); job {}; output {}", kVersion, o.command, comm.size,
               o.job, out.string());
  spdlog::info("resolved job:\n{}", job.resolved_toml());
  return out;
}

}  // namespace app
