// bench_farm partition: the farm's partitioning and rebalance check at many RVEs, serial (a
// program, never a test; usage in bench_farm.cpp).
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_farm_args.hpp"
#include "farm/partition.hpp"
#include "farm/rebalance.hpp"

namespace bench_farm {

// METIS on the RVE graph at --rves RVEs (serial, as on rank 0): graph build, the start-up
// partition, then a rebalance check after the costs changed: --perturb noise (default: every cost
// x [0.7, 1.3], deterministic) or --perturb overload (part 0's RVEs x (1 + --overload, 0.1)).
// Prints both proposals of the check (incremental from the current owners; METIS + renaming):
// RVEs moved, imbalance, time, and the bytes the chosen one carries (--bytes-per-rve: a
// 1000-sphere RVE's state).
void partition(const Args& a) {
  const int n = std::stoi(a.get("rves", "1000"));
  const int parts = std::stoi(a.get("parts", "32"));
  const double bytes_per_rve = std::stod(a.get("bytes-per-rve", "266000"));
  const std::string perturb = a.get("perturb", "noise");
  const Lattice lat = lattice(n);
  double t = now();
  const farm::RveGraph g = farm::cell_graph(lat.grid, lat.x);
  const double t_graph = now() - t;
  std::uint64_t lcg = 12345;
  auto uniform = [&lcg] {
    lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(lcg >> 11) / 9007199254740992.0;
  };
  std::vector<double> cost(static_cast<std::size_t>(n));
  for (double& c : cost) c = 1.0 + uniform();
  t = now();
  const std::vector<int> owner = farm::partition_metis(g, cost, parts);
  const double t_metis = now() - t;
  const double balance = farm::balance_efficiency(owner, cost, parts);
  if (perturb == "noise") {
    for (double& c : cost) c *= 0.7 + 0.6 * uniform();
  } else if (perturb == "overload") {
    const double over = std::stod(a.get("overload", "0.1"));
    for (std::size_t k = 0; k < cost.size(); ++k) cost[k] *= owner[k] == 0 ? 1.0 + over : 1.0;
  } else {
    throw std::runtime_error("--perturb " + perturb + ": must be noise or overload");
  }
  // The renaming alone (keep_owners, finding 1 of docs/validation/scaling.md) on a fresh METIS
  // partition.
  std::vector<int> proposal = farm::partition_metis(g, cost, parts);
  t = now();
  const std::int64_t kept_moves = farm::keep_owners(owner, proposal, parts);
  const double t_keep = now() - t;
  const double threshold = std::stod(a.get("threshold", "1.0"));
  t = now();
  const farm::RebalancePlan plan = farm::plan_rebalance(g, owner, cost, parts, threshold, 1);
  const double t_plan = now() - t;
  std::printf("partition: %d RVEs, %zu graph edges, %d parts\n", n, g.adjncy.size() / 2, parts);
  std::printf(
      "  cell_graph %.4f s, partition_metis %.4f s (balance %.3f), plan_rebalance %.4f s "
      "(of which keep_owners %.4f s)\n",
      t_graph, t_metis, balance, t_plan, t_keep);
  std::printf("  rebalance check after %s (threshold %.2f): imbalance now %.4f\n",
              perturb == "noise" ? "+/-30 % cost noise" : "an overload of part 0", threshold,
              plan.imbalance_now);
  const auto row = [&](const char* name, const farm::RebalanceProposal& p) {
    std::printf("    %-12s imbalance %.4f, %lld RVEs moved (%.2f %%), %.4f s%s\n", name,
                p.imbalance, static_cast<long long>(p.moves),
                100.0 * static_cast<double>(p.moves) / n, p.time_s,
                p.beats_margin ? "" : " (gain within the noise margin)");
  };
  row("incremental", plan.incremental);
  row("METIS", plan.metis);
  std::printf(
      "  chosen: %s, migrate %d, %lld RVEs moved (%.1f %%; renamed METIS proposal alone %lld) = "
      "%.1f MB at %.0f B per RVE\n",
      farm::to_string(plan.method), plan.migrate ? 1 : 0, static_cast<long long>(plan.moves),
      100.0 * static_cast<double>(plan.moves) / n, static_cast<long long>(kept_moves),
      static_cast<double>(plan.moves) * bytes_per_rve / 1e6, bytes_per_rve);
}

}  // namespace bench_farm
