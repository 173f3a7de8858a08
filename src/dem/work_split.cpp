#include "dem/work_split.hpp"

#include <algorithm>

namespace dem {

void WorkSplit::prepare(int threads, std::int64_t units) {
  const auto t = static_cast<std::size_t>(std::max(1, threads));
  const std::int64_t old_units = cut_.back();
  if (time_.size() == t && old_units == units) return;
  if (time_.size() == t && old_units > 0) {
    // The same team, another count (a rebuilt pair list): each boundary keeps its fraction.
    for (std::size_t k = 1; k < t; ++k) cut_[k] = cut_[k] * units / old_units;
    cut_[t] = units;
    for (std::size_t k = 1; k <= t; ++k) cut_[k] = std::max(cut_[k], cut_[k - 1]);
  } else {
    cut_.assign(t + 1, 0);
    const auto tt = static_cast<std::int64_t>(t);
    for (std::size_t k = 0; k <= t; ++k) cut_[k] = units * static_cast<std::int64_t>(k) / tt;
    time_.assign(t, 0.0);
  }
  std::fill(time_.begin(), time_.end(), 0.0);
  steps_ = 0;
}

void WorkSplit::rebalance() {
  if (++steps_ < kWindow) return;
  steps_ = 0;
  const std::size_t t = time_.size();
  double total = 0.0;
  for (const double x : time_) total += x;
  const std::int64_t units = cut_[t] - cut_[0];
  if (t > 1 && units > 0 && total > 0.0) {
    // A difference below one unit's cost cannot be mended; one below kDeadBand of a thread's
    // mean time is taken for noise (else the cut of a loop of many units wanders with it).
    const double band =
        std::max(total / static_cast<double>(units), kDeadBand * total / static_cast<double>(t));
    for (std::size_t k = 1; k < t; ++k) {
      const double d = time_[k - 1] - time_[k];
      if (d > band && cut_[k] > cut_[k - 1]) {
        --cut_[k];  // thread k - 1 was slower: thread k takes its last unit
      } else if (-d > band && cut_[k] < cut_[k + 1]) {
        ++cut_[k];
      }
    }
  }
  std::fill(time_.begin(), time_.end(), 0.0);
}

}  // namespace dem
