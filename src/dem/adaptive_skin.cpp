// The adaptive Verlet skin (docs/design/dem.md "Neighbour search").
#include "dem/adaptive_skin.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

double optimal_skin(const SkinInputs& in) {
  if (in.shell_pairs <= 0 || in.spheres <= 0 || !(in.skin > 0.0)) return in.hi;
  const double k =
      static_cast<double>(in.shell_pairs) / (static_cast<double>(in.spheres) * in.skin);
  const double v = in.measure / static_cast<double>(std::max<std::int64_t>(in.steps, 1));
  // v may be +inf (a position that is not finite: the rebuild names it); then hi.
  const double s = std::sqrt(kRebuildPairCost * v / k);
  return s == s ? std::clamp(s, in.lo, in.hi) : in.hi;
}

SkinDecision decide_skin(const SkinInputs& in) {
  const bool due = in.measure >= in.skin || in.measure != in.measure;
  if (due) return {true, optimal_skin(in)};
  if (in.steps >= kSkinMinSteps) {
    const double s = optimal_skin(in);
    if (s < 0.5 * in.skin) return {true, s};
  }
  return {false, in.skin};
}

}  // namespace dem
