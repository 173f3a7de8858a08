// When to repartition the RVEs: per-RVE costs are smoothed over check windows, and a new partition
// is adopted only when its predicted gain is above the measurement noise.
//
// A window of check_every MPM steps (~0.1 s of DEM) times every RVE with a noise of several per
// cent; deciding on one window moved 1347 identical RVEs in one 30 % run (issue 5). The cost of an
// RVE belongs to the RVE, not to its rank, so the average survives a migration.
#pragma once

#include <cstdint>
#include <vector>

#include "farm/partition.hpp"

namespace farm {

/// Exponentially weighted per-RVE cost: after each window, avg = decay * avg + window (the first
/// window starts it). With decay 0.8 the average spans ~5 windows (1 / (1 - decay)).
class CostAverage {
 public:
  explicit CostAverage(double decay = 0.8) : decay_(decay) {}
  /// Adds one window of measured costs (seconds per RVE, by index) [s].
  void add_window(const std::vector<double>& window);
  /// Average cost per RVE (arbitrary scale: only ratios matter); empty before any window.
  [[nodiscard]] const std::vector<double>& cost() const { return avg_; }
  [[nodiscard]] int windows() const { return windows_; }
  /// Enough windows for a decision (kSettledWindows): the first windows carry the start-up's
  /// noise alone (a one-window average moved 6 of 8 identical RVEs at step 20 in a benchmark).
  [[nodiscard]] bool settled() const { return windows_ >= kSettledWindows; }
  static constexpr int kSettledWindows = 3;

 private:
  double decay_;
  std::vector<double> avg_;
  int windows_ = 0;
};

/// What a migration costs and what a better partition is worth, measured by the farm: a move
/// must pay for itself within the time the partition is expected to last. It refuses small gains
/// on short-lived partitions and dear moves (large RVEs); it does not stop the paper's job at
/// threshold 1.05 from chasing the post-peak flicker of the costs, whose moves are cheap
/// (docs/design/farm.md, "Balancing").
struct Payback {
  double step_s = 0.0;          ///< RVE time of the critical rank per MPM step, recent [s]
  double horizon_steps = 0.0;   ///< steps the new partition is expected to last [-]
  double move_s_per_rve = 0.0;  ///< measured time to move one RVE [s]; 0: not measured (free)
};

/// Which proposal a check chose: none (no proposal, or none beat the noise margin), the
/// incremental repartition from the current owners (partition_incremental), or a fresh METIS
/// partition renamed after the current owners (partition_metis + keep_owners).
enum class RebalanceMethod { none, incremental, metis };
/// "none", "incremental", "METIS" (log lines).
[[nodiscard]] const char* to_string(RebalanceMethod m);

/// One candidate partition of a check.
struct RebalanceProposal {
  double imbalance = 1.0;     ///< max/mean of its part loads [-]
  std::int64_t moves = 0;     ///< RVEs it moves (after renaming, for METIS)
  double saving_s = 0.0;      ///< predicted: step_s (1 - imbalance / now) horizon_steps [s]
  double move_s = 0.0;        ///< predicted: moves * move_s_per_rve [s]
  double time_s = 0.0;        ///< wall time to compute it (METIS: with the renaming) [s]
  bool beats_margin = false;  ///< lowers the imbalance by more than the noise margin, moves > 0
};

/// The decision of one check. The imbalance_new / moves / saving_s / move_s fields describe the
/// chosen proposal (`method`), adopted or not (payback may refuse it); both candidates are kept.
struct RebalancePlan {
  bool migrate = false;
  std::vector<int> owner;      ///< the new owners when migrate, else the current ones
  double imbalance_now = 1.0;  ///< max/mean of part loads with the current owners [-]
  double imbalance_new = 1.0;  ///< the same for the chosen proposal [-]
  std::int64_t moves = 0;      ///< RVEs the chosen proposal moves
  double saving_s = 0.0;       ///< predicted: step_s (1 - new / now) horizon_steps [s]
  double move_s = 0.0;         ///< predicted: moves * move_s_per_rve [s]
  double proposal_s = 0.0;     ///< wall time of both proposals (METIS dominates); 0: none made [s]
  RebalanceMethod method = RebalanceMethod::none;  ///< the chosen proposal
  RebalanceProposal incremental;                   ///< partition_incremental from the owners
  RebalanceProposal metis;  ///< the fresh partition (partition_fresh) + keep_owners
  PartitionStyle style = PartitionStyle::cells;  ///< of the fresh proposal and the descent
};

/// The name of the fresh proposal in log lines: "METIS" (cells) or "spread".
[[nodiscard]] const char* fresh_name(PartitionStyle style);

/// How close to a perfect balance plan_rebalance takes the incremental descent: it runs to
/// imbalance 1 + kDescentSlack / 2 at most, and when the pay is unknown it is cut at its first
/// state within kDescentSlack / 2 of where it ended (descent_cut). So where the descent gets
/// there, its proposal is within kDescentSlack, the smallest noise margin (0.01 / 2), of any
/// partition METIS can find: the last steps, swaps of nearly equal RVEs, gain less than that for
/// many RVEs moved.
inline constexpr double kDescentSlack = 0.005;

/// Proposes two partitions of `cost` once the current imbalance exceeds `threshold`: the
/// incremental repartition from `owner` (incremental_descent to 1 + kDescentSlack / 2, then cut
/// where the net payback is best among its states that beat the margin when `pay` is known, else
/// by descent_cut with kDescentSlack) and a fresh METIS partition renamed after
/// `owner` (`style` spread: the descent ignores the graph, which would pull RVEs to their
/// neighbours' parts, and the fresh partition is partition_spread). A proposal qualifies when it
/// lowers the imbalance by more than the margin max(threshold
/// - 1, 0.01) / 2 (a smaller gain is the noise a threshold is set against) and moves something.
/// Where `pay` is known (step_s and move_s_per_rve > 0) the qualifying proposal with the larger net
/// payback (saving_s - move_s) is chosen (ties: fewer moves, then incremental) and adopted only if
/// its net is positive; where it is not, the one that moves fewer RVEs is chosen (ties:
/// incremental) unless the other's imbalance is lower by more than the margin, and adopted.
/// threshold <= 1 only keeps the 0.005 margin.
/// @pre cost.size() == owner.size() == graph.size()
[[nodiscard]] RebalancePlan plan_rebalance(const RveGraph& graph, const std::vector<int>& owner,
                                           const std::vector<double>& cost, int nparts,
                                           double threshold, int seed, const Payback& pay = {},
                                           PartitionStyle style = PartitionStyle::cells);

/// Max over mean of the part loads (>= 1; 1 when every load is zero) [-].
[[nodiscard]] double imbalance(const std::vector<int>& owner, const std::vector<double>& cost,
                               int nparts);

}  // namespace farm
