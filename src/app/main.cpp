// mpmxdem entry point: MPI set-up, command-line parsing, dispatch, and the error policy
// (input errors: message on rank 0, exit 2; numerical failures: exit 3; I/O failures: exit 4;
// anything else: MPI_Abort, exit 1).
#include <mpi.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "app/commands/cli.hpp"
#include "app/commands/commands.hpp"
#include "app/run/logging.hpp"
#include "app/run/output_dir.hpp"
#include "common/errors.hpp"
#include "common/heap.hpp"

int main(int argc, char** argv) {
  // Before anything allocates: freed memory stays with the process (neighbour-list builds and
  // migrations reuse it instead of faulting fresh pages in; common/heap.hpp).
  common::keep_freed_memory();
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  app::Comm comm;
  MPI_Comm_rank(comm.comm, &comm.rank);
  MPI_Comm_size(comm.comm, &comm.size);

  int code = 0;
  const auto options = app::parse_cli(argc, argv, comm.rank == 0, code);
  if (!options) {
    MPI_Finalize();
    return code;
  }
  app::setup_logging(comm.rank, options->verbosity);
  try {
    if (options->command == "check") {
      code = app::command_check(*options, comm);
    } else if (options->command == "run") {
      code = app::command_run(*options, comm);
    } else if (options->command == "dem") {
      code = app::command_dem(*options, comm);
    } else if (options->command == "bench") {
      code = app::command_bench(*options, comm);
    } else if (options->command == "inspect") {
      code = app::command_inspect(*options, comm);
    } else if (options->command == "schema") {
      code = app::command_schema(*options, comm);
    }
  } catch (const common::InputError& e) {
    // Input errors are collective: every rank read the same input and threw the same error.
    if (comm.rank == 0) std::fprintf(stderr, "error: %s\n", e.what());
    code = 2;
    // A run refused after its output directory was opened leaves nothing behind.
    if (comm.rank == 0) {
      app::remove_log_file();
      const std::string undone = app::discard_refused_output();
      if (!undone.empty()) std::fprintf(stderr, "nothing written: %s\n", undone.c_str());
    }
  } catch (const common::NumericalError& e) {
    // Numerical failures reach every rank through the farm's error agreement: rank 0 reports.
    if (comm.rank == 0) spdlog::error("numerical failure: {}", e.what());
    code = 3;
  } catch (const common::IoError& e) {
    // The system failed to store a file (disk full, I/O error): agreed across ranks like the two
    // above (farm::ErrorKind::io), so every rank exits cleanly.
    if (comm.rank == 0) std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    code = 4;
  } catch (const std::bad_alloc&) {
    // Out of memory on this rank (other ranks may be waiting in a collective): say so plainly and
    // take the whole job down.
    std::fprintf(stderr,
                 "rank %d: fatal: out of memory (std::bad_alloc): this rank could not allocate "
                 "what the job needs; use more nodes or fewer ranks per node, or a smaller job\n",
                 comm.rank);
    std::fflush(stderr);
    MPI_Abort(comm.comm, 1);
  } catch (const std::exception& e) {
    // A failure that only this rank may have seen: report it and take the whole job down.
    std::fprintf(stderr, "rank %d: fatal: %s\n", comm.rank, e.what());
    std::fflush(stderr);
    MPI_Abort(comm.comm, 1);
  } catch (...) {
    std::fprintf(stderr, "rank %d: fatal: unknown exception\n", comm.rank);
    std::fflush(stderr);
    MPI_Abort(comm.comm, 1);
  }
  MPI_Finalize();
  return code;
}
