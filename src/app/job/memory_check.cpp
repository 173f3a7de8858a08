#include "app/job/memory_check.hpp"

#include <fmt/format.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "common/errors.hpp"

namespace app {
namespace {

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

// The first number of a file, or 0 if it holds none ("max": no limit).
double number_in(const std::string& path) {
  std::ifstream in(path);
  double v = 0.0;
  return in >> v ? v : 0.0;
}

// This process's cgroup memory limit [B], 0 if none or unknown. /proc/self/cgroup lines are
// "0::/path" (v2) or "N:memory:/path" (v1); the controllers are mounted under /sys/fs/cgroup.
double cgroup_limit_bytes() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  double limit = 0.0;
  auto take = [&](double v) {
    // v1 writes "no limit" as a huge number (2^63 rounded to pages).
    if (v > 0.0 && v < 1e18) limit = limit > 0.0 ? std::min(limit, v) : v;
  };
  while (std::getline(in, line)) {
    const auto a = line.find(':');
    const auto b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    const std::string path = line.substr(b + 1);
    if (controllers.empty()) {
      take(number_in("/sys/fs/cgroup" + path + "/memory.max"));
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      take(number_in("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes"));
    }
  }
  return limit;
}

}  // namespace

double usable_memory_bytes() {
  const double physical = physical_memory_bytes();
  const double cgroup = cgroup_limit_bytes();
  if (physical > 0.0 && cgroup > 0.0) return std::min(physical, cgroup);
  return std::max(physical, cgroup);
}

std::string format_bytes(double bytes) { return fmt::format("{:.3g} GB", bytes / 1e9); }

void check_rve_memory(const Job& job, const RveMemory& m, const Comm& comm) {
  // The ranks of each node: what they hold together, against the node's memory (the same on
  // every rank of a node; a node's control group is shared by its ranks).
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm.comm, MPI_COMM_TYPE_SHARED, comm.rank, MPI_INFO_NULL, &node);
  std::int64_t rves_here = 0;
  MPI_Allreduce(&m.held, &rves_here, 1, MPI_INT64_T, MPI_SUM, node);
  int ranks_here = 1;
  MPI_Comm_size(node, &ranks_here);
  MPI_Comm_free(&node);
  const double need =
      static_cast<double>(rves_here) * static_cast<double>(m.spheres) * kRveBytesPerSphere;
  const double mem = usable_memory_bytes();
  // The node most over its memory, told to every rank (the same message everywhere).
  struct {
    double ratio;
    int rank;
  } mine{mem > 0.0 ? need / mem : 0.0, comm.rank}, worst{};
  MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm.comm);
  if (!(worst.ratio > 1.0)) return;
  double figures[4] = {static_cast<double>(rves_here), static_cast<double>(ranks_here), need, mem};
  MPI_Bcast(figures, 4, MPI_DOUBLE, worst.rank, comm.comm);
  const double total =
      static_cast<double>(m.rves) * static_cast<double>(m.spheres) * kRveBytesPerSphere;
  throw common::InputError(job.message(
      m.key,
      fmt::format("the run's {} DEM RVEs of {} spheres need at least {} of memory ({:.0f} bytes "
                  "per sphere), and the {:.0f} rank(s) on the node of rank {} would hold {:.0f} of "
                  "them at the start: at least {}, more than the {} this node lets the job use "
                  "(physical memory, or the batch job's limit); use more nodes (ranks on "
                  "separate nodes), fewer material points or smaller RVEs",
                  m.rves, m.spheres, format_bytes(total), kRveBytesPerSphere, figures[1],
                  worst.rank, figures[0], format_bytes(figures[2]), format_bytes(figures[3]))));
}

}  // namespace app
