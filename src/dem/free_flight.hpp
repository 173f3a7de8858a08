// Free flight of a periodic cell without contacts: whether one DEM step of length dt with the
// cell's velocity gradient L moves every sphere as the n shorter steps it replaces would, i.e.
// whether no pair can come into contact within it (docs/design/rve_step.md, "Free flight").
#pragma once

#include "common/types.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// Whether a step of `dt` [s] under the velocity gradient `l` [1/s] is free flight for `sim`:
/// - no contact is active now (the spheres' forces are zero, so their velocities stay);
/// - every pair of the neighbour list stays apart over the whole step: within a step the branch
///   x_j + H k - x_i moves linearly in time, d(t) = d0 + t (u_j - u_i + L d0), so its closest
///   approach on [0, dt] is exact; it must stay above r_i + r_j by `margin` times r_i + r_j;
/// - no pair outside the list can touch: the list's drift measure (2 max|a| + ||F - I|| (2 r_max
///   + skin), neighbor_search.hpp) is below the skin at both ends of the step, hence during it (the
///   drift a and F are linear in t, the measure convex).
/// False when the list is not current (a rebuild is pending, or it was built for other spheres).
/// The step itself (x <- x + dt (u + L x), H <- (I + L dt) H) differs from n steps of dt / n by
/// O((|L| dt)^2) relative to the branches: `margin` must cover it (Rve uses 4 (max|L dt|)^2 +
/// 1e-12). @pre dt >= 0, l finite.
[[nodiscard]] bool free_flight_holds(const Simulation& sim, double dt, const common::Mat3& l,
                                     double margin);

}  // namespace dem
