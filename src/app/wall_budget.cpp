#include "app/wall_budget.hpp"

#include <algorithm>

namespace app {

bool WallBudget::spent(Clock::time_point now) {
  using Seconds = std::chrono::duration<double>;
  if (called_) longest_ = std::max(longest_, Seconds(now - last_).count());
  called_ = true;
  last_ = now;
  const double left = budget_ - Seconds(now - start_).count();
  return left < 2.0 * longest_ + 0.01 * budget_;
}

}  // namespace app
