// MPI helpers of the farm (see header).
#include "farm/mpi_util.hpp"

#include <omp.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <exception>
#include <thread>

#include "common/errors.hpp"

namespace farm {

namespace {
constexpr std::chrono::microseconds kPollBudget{200};
}  // namespace

void wait_for(MPI_Request& request, WaitMode mode) {
  if (mode == WaitMode::spin) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
    return;
  }
  int done = 0;
  // Poll for up to kPollBudget first: most waits of a step are that short (a worker waiting for
  // rank 0's MPM step, rank 0 waiting for a slightly slower worker) and end with no latency.
  // Then sleep with an exponential back-off capped at 100 us, so a long wait leaves its core to
  // the DEM of another rank yet notices its end within ~0.15 ms (with Linux timer slack).
  // Measured (docs/design/farm.md): 20 polls only cost 0.16 ms of latency per MPM step, this 0.03
  // ms.
  const auto start = std::chrono::steady_clock::now();
  while (done == 0 && std::chrono::steady_clock::now() - start < kPollBudget) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
  auto pause = std::chrono::microseconds(10);
  while (done == 0) {
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(100));
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
}

void throw_kind(ErrorKind kind, const std::string& message) {
  switch (kind) {
    case ErrorKind::input:
      throw common::InputError(message);
    case ErrorKind::numerical:
      throw common::NumericalError(message);
    case ErrorKind::io:
      throw common::IoError(message);
    default:
      throw common::InternalError(message);
  }
}

ErrorKind current_error_kind() {
  try {
    throw;
  } catch (const common::InputError&) {
    return ErrorKind::input;
  } catch (const common::NumericalError&) {
    return ErrorKind::numerical;
  } catch (const common::IoError&) {
    return ErrorKind::io;
  } catch (...) {
    return ErrorKind::internal;
  }
}

void agree_on_errors(MPI_Comm comm, ErrorKind kind, const std::string& message) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = kind == ErrorKind::none ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  std::string msg = message;
  auto k = static_cast<std::int32_t>(kind);
  MPI_Bcast(&k, 1, MPI_INT32_T, first, comm);
  bcast_string(comm, msg, first);
  throw_kind(static_cast<ErrorKind>(k), msg);
}

void bcast_string(MPI_Comm comm, std::string& s, int root) {
  auto n = static_cast<std::int64_t>(s.size());
  MPI_Bcast(&n, 1, MPI_INT64_T, root, comm);
  s.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(s.data(), to_count(s.size()), MPI_CHAR, root, comm);
}

std::vector<std::string> allgather_strings(MPI_Comm comm, const std::vector<std::string>& mine) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::string packed;
  for (const std::string& s : mine) {
    packed += s;
    packed.push_back('\0');
  }
  const int n = to_count(packed.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> displs(static_cast<std::size_t>(size), 0);
  std::int64_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = to_count(static_cast<std::size_t>(total));
    total += counts[r];
  }
  std::string all(static_cast<std::size_t>(total), '\0');
  MPI_Allgatherv(packed.data(), n, MPI_CHAR, all.data(), counts.data(), displs.data(), MPI_CHAR,
                 comm);
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i] == '\0') {
      out.emplace_back(all.substr(start, i - start));
      start = i + 1;
    }
  }
  return out;
}

const char* to_string(WaitMode mode) {
  return common::name_of(kWaitModeNames, mode).data();  // the names are literals
}

WaitMode wait_mode_from(const std::string& text) {
  if (const auto m = common::value_of(kWaitModeNames, text)) return *m;
  throw common::InputError("wait mode '" + text + "': must be one of " +
                           common::names_list(kWaitModeNames));
}

WaitMode resolve_wait_mode(MPI_Comm comm, WaitMode mode) {
  if (mode != WaitMode::automatic) return mode;
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  // The cores this rank may run on, as a bit mask; OR-ed over the node's ranks.
  constexpr int kWords = CPU_SETSIZE / 64;
  std::vector<std::uint64_t> mask(kWords, 0);
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    for (int c = 0; c < CPU_SETSIZE; ++c) {
      if (CPU_ISSET(c, &set))
        mask[static_cast<std::size_t>(c / 64)] |= std::uint64_t{1} << (c % 64);
    }
  } else {
    for (int c = 0; c < std::min(omp_get_num_procs(), CPU_SETSIZE); ++c)
      mask[static_cast<std::size_t>(c / 64)] |= std::uint64_t{1} << (c % 64);
  }
  MPI_Allreduce(MPI_IN_PLACE, mask.data(), kWords, MPI_UINT64_T, MPI_BOR, node);
  int threads = omp_get_max_threads();
  MPI_Allreduce(MPI_IN_PLACE, &threads, 1, MPI_INT, MPI_SUM, node);
  MPI_Comm_free(&node);
  int cores = 0;
  for (const std::uint64_t w : mask) cores += __builtin_popcountll(w);
  return threads <= cores ? WaitMode::spin : WaitMode::sleep;
}

int threads_per_rank(MPI_Comm comm) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int local = 1;
  MPI_Comm_size(node, &local);
  // Ranks bound to one core each see 1 proc; unbound ranks see the whole node and share it.
  const int procs = omp_get_num_procs();
  int max_procs = procs;
  MPI_Allreduce(&procs, &max_procs, 1, MPI_INT, MPI_MAX, node);
  MPI_Comm_free(&node);
  const int share = procs >= max_procs && max_procs > 1 ? procs / local : procs;
  return std::max(1, share);
}

int to_count(std::size_t n) {
  MPMXDEM_CHECK(n <= static_cast<std::size_t>(INT_MAX),
                "MPI message of " + std::to_string(n) + " elements exceeds INT_MAX");
  return static_cast<int>(n);
}

}  // namespace farm
