// Partition of the RVEs over ranks: METIS k-way on the graph of RVEs (vertex weight = cost, an
// edge between two RVEs whose material points share a grid cell), an incremental repartition from
// the current owners, plus simple reference splits.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/choice_table.hpp"
#include "common/types.hpp"
#include "mpm/grid.hpp"

namespace farm {

/// CSR adjacency over RVEs 0..n-1 (METIS layout, symmetric, no self loops, sorted rows).
struct RveGraph {
  std::vector<std::int64_t> xadj;    ///< n + 1 row offsets
  std::vector<std::int64_t> adjncy;  ///< neighbours
  [[nodiscard]] std::size_t size() const { return xadj.empty() ? 0 : xadj.size() - 1; }
};

/// RVE k sits at x[k]; RVEs whose points lie in the same grid cell are neighbours.
[[nodiscard]] RveGraph cell_graph(const mpm::Grid& grid, const std::vector<common::Vec3>& x);

/// Owner rank of every RVE, in [0, nparts). METIS_PartGraphKway with METIS_OPTION_SEED = seed
/// (deterministic for the same input); nparts == 1 is handled here (METIS crashes on it), and
/// nparts >= n puts one RVE per part. Costs are scaled to 32-bit integer weights >= 1.
/// METIS's answer is then refined for balance (refine_balance).
/// @pre cost.size() == graph.size(), every cost finite and >= 0, nparts >= 1
[[nodiscard]] std::vector<int> partition_metis(const RveGraph& graph,
                                               const std::vector<double>& cost, int nparts,
                                               int seed = 1);
/// How RVEs are grouped on a rank. cells: METIS's contiguous parts of the cell graph (neighbours
/// together). spread: neighbours apart (partition_spread). An RVE's cost per MPM step follows its
/// strain increment, which neighbouring points share (correlation 0.7 between graph neighbours
/// in the 8 x 16 biaxial), so a contiguous part sums correlated fluctuations and its step time
/// swings far more than a spread part's (docs/design/farm.md, "Balancing"). RVEs exchange
/// nothing with each other: the grouping changes no result and no message size.
enum class PartitionStyle { cells, spread };
/// The job's names (farm.partition).
inline constexpr std::array<common::Named<PartitionStyle>, 2> kPartitionStyleNames{
    {{"spread", PartitionStyle::spread}, {"cells", PartitionStyle::cells}}};
/// "cells" / "spread"; parse_partition_style throws common::InputError on other text.
[[nodiscard]] const char* to_string(PartitionStyle s);
[[nodiscard]] PartitionStyle parse_partition_style(const std::string& s);

/// Balanced by cost with graph neighbours on different parts: METIS cuts the graph into
/// ceil(n / nparts) tiles of about nparts neighbouring RVEs (equal weights), then each tile's
/// RVEs, costliest first, go to the lightest part the tile has not used yet (ties: lowest part;
/// a tile larger than nparts starts over), then refine_balance. Deterministic for the same
/// input; nparts == 1 and nparts >= n as partition_metis.
/// @pre as partition_metis
[[nodiscard]] std::vector<int> partition_spread(const RveGraph& graph,
                                                const std::vector<double>& cost, int nparts,
                                                int seed = 1);
/// A fresh partition in `style`: partition_metis (cells) or partition_spread.
[[nodiscard]] std::vector<int> partition_fresh(PartitionStyle style, const RveGraph& graph,
                                               const std::vector<double>& cost, int nparts,
                                               int seed = 1);

/// Greedy balance refinement after METIS (whose k-way balance slips with few heavy vertices):
/// moves RVEs from the heaviest part to the lightest while that lowers their maximum. Only
/// balance counts here (RVEs exchange nothing with each other; the cut is a secondary goal).
void refine_balance(std::vector<int>& owner, const std::vector<double>& cost, int nparts);
/// One step of the incremental descent (incremental_descent).
struct DescentStep {
  std::size_t rve = 0;      ///< the RVE moved
  int to = 0;               ///< its new part
  bool ends_a_move = true;  ///< false for the first half of a swap: not a state to stop in
  double max_load = 0.0;    ///< largest part load after the step (where ends_a_move)
  std::int64_t moved = 0;   ///< RVEs away from their starting part after the step
};

/// Incremental (diffusive) repartition from the current owners: moves RVEs one at a time out of
/// the heaviest part (ties: lowest label) while a move lowers the larger of the two loads it
/// changes, so it moves only what the balance needs (a fresh METIS partition moves 35-95 % of the
/// RVEs for a few per cent of gain: docs/validation/scaling.md, finding 2). A move takes an RVE of
/// the heaviest part to the lightest part or to a part owning one of its graph neighbours; the move
/// chosen is the first by (1) the largest part load after it, (2) a neighbour part before the
/// lightest, (3) the larger of the two changed loads, (4) the lowest RVE index, (5) the lowest
/// part. When no RVE of the heaviest part fits anywhere (few RVEs per part), it swaps one with a
/// cheaper RVE of the lightest part, the pair whose cost difference best evens the two loads.
/// Stops when neither lowers the pair's max, or once the imbalance (max/mean load) is at most
/// `stop_imbalance` (1: only at the local optimum). Returns the steps in order. Deterministic (no
/// threads; the order of the members does not matter); the maximum load never increases (every
/// move or swap lowers the sum of squared loads, so the descent ends); RVEs of zero cost stay.
/// @pre owner.size() == cost.size() == graph.size(), owners in [0, nparts), costs finite and >= 0
[[nodiscard]] std::vector<DescentStep> incremental_descent(const RveGraph& graph,
                                                           const std::vector<int>& owner,
                                                           const std::vector<double>& cost,
                                                           int nparts, double stop_imbalance = 1.0);
/// `owner` after the first `count` steps of a descent started from it.
[[nodiscard]] std::vector<int> apply_descent(std::vector<int> owner,
                                             const std::vector<DescentStep>& steps,
                                             std::size_t count);
/// How many leading steps of a descent to keep: up to its first complete state whose maximum
/// load is within slack / 2 x `mean_load` of where it ended (0 if it made none). The last steps
/// of a descent, swaps of nearly equal RVEs, gain little per RVE moved.
[[nodiscard]] std::size_t descent_cut(const std::vector<DescentStep>& steps, double mean_load,
                                      double slack);
/// The incremental repartition within `slack` of a perfect balance where the descent can get
/// there: incremental_descent stopped at imbalance 1 + slack / 2, then cut by descent_cut (within
/// slack / 2 of its end). slack = 0: the shortest prefix of the whole descent that reaches its
/// final maximum load.
/// @pre as incremental_descent; slack >= 0
[[nodiscard]] std::vector<int> partition_incremental(const RveGraph& graph, std::vector<int> owner,
                                                     const std::vector<double>& cost, int nparts,
                                                     double slack = 0.0);
/// Renames the parts of `proposal` so that as many RVEs as possible keep their `current` owner
/// (part labels are arbitrary to METIS; ranks are interchangeable for balance): greedy matching
/// of new to old labels by the RVEs they share, largest first (ties: lowest labels).
/// Returns the number of RVEs the renamed proposal moves.
std::int64_t keep_owners(const std::vector<int>& current, std::vector<int>& proposal, int nparts);
/// RVE k on rank k % nparts.
[[nodiscard]] std::vector<int> partition_round_robin(std::size_t n, int nparts);
/// Contiguous blocks of nearly equal counts (the start-up split before costs are known).
[[nodiscard]] std::vector<int> partition_blocks(std::size_t n, int nparts);

/// Sum of costs per part.
[[nodiscard]] std::vector<double> part_loads(const std::vector<int>& owner,
                                             const std::vector<double>& cost, int nparts);
/// Load-balance efficiency mean/max of part loads, in (0, 1]; 1 when all loads are zero.
[[nodiscard]] double balance_efficiency(const std::vector<int>& owner,
                                        const std::vector<double>& cost, int nparts);

}  // namespace farm
