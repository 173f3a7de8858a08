// The Verlet skin adapted to how fast an RVE's spheres move (dem.numerics.verlet_skin_min): a
// wide skin keeps a list valid long in a flow, a thin one keeps few pairs in a cell that barely
// moves. Chosen from the cell's own state only (the drift measured since the last build, the
// steps it took, the pairs the last build found outside contact), so that thread counts, rank
// counts and restarts keep their bits.
#pragma once

#include <cstdint>

namespace dem {

/// The cost of a list build, in pair evaluations per sphere (a step costs about 1.3 + the pairs
/// per sphere of them): the model's one constant. Measured on the reference packing, one thread:
/// a build 1356 us, 13.4 steps; a pair 19 ns (docs/design/dem.md "Neighbour search").
inline constexpr double kRebuildPairCost = 70.0;
/// Steps a list must have lasted before it may be rebuilt early with a thinner skin (a shorter
/// history measures no rate).
inline constexpr std::int64_t kSkinMinSteps = 100;

/// What the neighbour check decides at a step.
struct SkinDecision {
  bool rebuild = false;  ///< build the list now
  double skin = 0.0;     ///< with this skin [m]
};

/// The list's state that the choice reads.
struct SkinInputs {
  double measure = 0.0;          ///< 2 max|a| + ||F - I|| (2 r_max + skin), (rebuild_measure) [m]
  double skin = 0.0;             ///< the current list's skin [m]
  std::int64_t steps = 0;        ///< steps since the list was built
  std::int64_t shell_pairs = 0;  ///< pairs of the list not in contact when it was built
  std::int64_t spheres = 0;      ///< spheres of the cell
  double lo = 0.0;               ///< thinnest skin allowed [m]
  double hi = 0.0;               ///< widest skin allowed [m]
};

/// The skin minimising the modelled cost per step, pair work plus a build amortised over the
/// list's life: shell pairs per sphere grow as k s (k from the last build), the measure grows at
/// v = measure / steps, a list lives s / v steps, so cost(s) = k s + R v / s, least at
/// s* = sqrt(R v / k); clamped to [lo, hi] (hi when k = 0: no pair to save; lo when v = 0).
[[nodiscard]] double optimal_skin(const SkinInputs& in);

/// Rebuild when the measure reaches the skin (the list's guarantee), with the optimal skin; or
/// early, once the list has lasted kSkinMinSteps, when the optimal skin is below half the
/// current one (the cell moves far less than its skin allows: fewer pairs pay for the build).
/// The skin only shrinks early; it grows at the rebuilds the measure forces.
[[nodiscard]] SkinDecision decide_skin(const SkinInputs& in);

}  // namespace dem
