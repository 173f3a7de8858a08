// Small MPI helpers of the farm: waiting on a request without stealing a core, collective error
// agreement (one rank's failure becomes the same exception on every rank), string broadcast.
#pragma once

#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/choice_table.hpp"

namespace farm {

/// How a rank waits for a non-blocking collective.
enum class WaitMode {
  automatic,  ///< spin where every thread of the node's ranks has a core, sleep where they share
              ///< cores (resolve_wait_mode; docs/design/farm.md, "Waiting")
  spin,       ///< MPI_Wait: Open MPI busy-polls (a core at 100 %)
  sleep,      ///< polls MPI_Test for up to 200 us, then sleeps with a back-off from 10 us to
              ///< 100 us (a long wait frees the core)
};
/// The job's names (farm.wait).
inline constexpr std::array<common::Named<WaitMode>, 3> kWaitModeNames{
    {{"auto", WaitMode::automatic}, {"spin", WaitMode::spin}, {"sleep", WaitMode::sleep}}};

/// "auto", "spin", "sleep".
const char* to_string(WaitMode mode);
/// The inverse of to_string. Throws common::InputError for any other text.
WaitMode wait_mode_from(const std::string& text);

/// Collective over `comm`. `automatic` becomes `spin` when the OpenMP threads of the ranks that
/// share this rank's node (sum of omp_get_max_threads) fit in the cores they may run on (union of
/// their affinity masks), else `sleep`; other modes are returned as they are. Every rank of a node
/// gets the same answer.
WaitMode resolve_wait_mode(MPI_Comm comm, WaitMode mode);

/// Completes `request` according to `mode` (automatic is treated as sleep: resolve it first).
void wait_for(MPI_Request& request, WaitMode mode);

/// Error kinds that travel between ranks (exit codes differ in the app).
enum class ErrorKind : std::int32_t { none = 0, input = 1, numerical = 2, internal = 3, io = 4 };

/// Throws the exception type of `kind` (common::InputError, NumericalError, InternalError,
/// IoError) with `message`. @pre kind != none
[[noreturn]] void throw_kind(ErrorKind kind, const std::string& message);

/// Classifies the exception being handled (call inside a catch block).
ErrorKind current_error_kind();

/// Collective: if any rank passes a non-none kind, every rank throws the error of the lowest
/// such rank (same type, same message). Otherwise returns.
void agree_on_errors(MPI_Comm comm, ErrorKind kind, const std::string& message);

/// Broadcast a string from `root` (the one home of string broadcast: farm and app use it).
void bcast_string(MPI_Comm comm, std::string& s, int root = 0);

/// Every rank's strings, concatenated in rank order.
std::vector<std::string> allgather_strings(MPI_Comm comm, const std::vector<std::string>& mine);

/// OpenMP threads per rank that do not oversubscribe the node: the cores this rank may use
/// (omp_get_num_procs: its affinity mask) divided by the ranks sharing the node that see the same
/// cores, at least 1. Oversubscribed OpenMP barriers are ruinous: 2 ranks x 2 threads on 2 cores
/// ran the elastic triaxial job 35 times slower (3.5 s against 0.1 s). Collective over `comm`.
int threads_per_rank(MPI_Comm comm);

/// MPI int count from a size, with a check against overflow.
int to_count(std::size_t n);

}  // namespace farm
