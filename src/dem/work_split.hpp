// How a loop of the DEM step is cut between the threads of its team, moved by measured times.
// Which thread does an index never changes a result (each index's work is the same operations
// wherever it runs): only the waits at the barriers depend on the cut.
#pragma once

#include <cstdint>
#include <vector>

namespace dem {

/// Contiguous ranges of units (a unit: a stress block of pairs, or a few spheres) for the
/// threads of a team: thread t takes [cut[t], cut[t+1]). Starts even; every `window` steps the
/// boundary between two neighbouring threads moves by one unit toward the one that was faster,
/// when their times differ by more than one unit's mean cost (a move changes the difference by
/// two units' cost: the cut then stays put instead of oscillating) and by more than kDeadBand of
/// a thread's mean time (noise: a cut of 1000 units would wander with it, measured 2 % slower
/// at 8000 spheres without the band).
///
/// Why (docs/design/dem.md "Speed"): with the spheres in spatial order and pairs stored under their
/// lower index, the pairs that cross from one thread's spheres to the next thread's are all in
/// the lower thread's share, and they read spheres another core has just written: on this VM,
/// 2 threads at 1000 spheres, thread 0's half of the pairs took 27.5 us against 25.5 us.
class WorkSplit {
 public:
  static constexpr int kWindow = 16;  ///< steps whose times are summed before a move
  /// Differences below this fraction of a thread's mean time move nothing (noise).
  static constexpr double kDeadBand = 0.03;

  /// Sizes the cut for `threads` threads and `units` units: kept if both are unchanged, scaled
  /// (each boundary in proportion) if only the units changed, even otherwise. Call before the
  /// team reads range(): by one thread, outside the loop.
  void prepare(int threads, std::int64_t units);
  /// First unit of thread t and one past its last.
  [[nodiscard]] std::int64_t begin(int t) const { return cut_[static_cast<std::size_t>(t)]; }
  [[nodiscard]] std::int64_t end(int t) const { return cut_[static_cast<std::size_t>(t) + 1]; }
  /// Thread t's time on its range this step [any unit]: each thread writes its own entry.
  void record(int t, double time) { time_[static_cast<std::size_t>(t)] += time; }
  /// After the team's step, by one thread: counts the step and, at the end of a window, moves
  /// the boundaries and clears the sums.
  void rebalance();

  [[nodiscard]] const std::vector<std::int64_t>& cut() const { return cut_; }
  [[nodiscard]] int threads() const { return static_cast<int>(time_.size()); }

 private:
  std::vector<std::int64_t> cut_{0, 0};
  std::vector<double> time_{0.0};
  int steps_ = 0;
};

}  // namespace dem
