#include "app/run/wall_budget.hpp"

#include <algorithm>

namespace app {

bool WallBudget::spent(Clock::time_point now) {
  using Seconds = std::chrono::duration<double>;
  const bool first = !called_;
  if (!first) longest_ = std::max(longest_, Seconds(now - last_).count());
  called_ = true;
  last_ = now;
  // Before the run's first step nothing stops it: a start longer than the budget would otherwise
  // end every link of a chain where it began.
  if (first) return false;
  const double left = budget_ - Seconds(now - start_).count();
  return left < 2.0 * longest_ + 0.01 * budget_;
}

}  // namespace app
