// Neighbour search: Verlet pair lists with a skin, built over bins in reduced (fractional)
// coordinates of a possibly sheared periodic cell; rebuilt only when displacements or the cell
// deformation since the last build exceed what the skin allows.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "common/types.hpp"
#include "dem/contacts.hpp"
#include "dem/periodic_cell.hpp"
#include "dem/spheres.hpp"

namespace dem {

/// Reference state of the last build, for the rebuild criterion.
struct VerletState {
  std::vector<common::Vec3> x_ref;                    ///< positions at the last build [m]
  common::Mat3 h_ref_inv = common::Mat3::Identity();  ///< inverse cell matrix at the last build
  double skin = 0.0;                                  ///< skin distance [m]
  double r_max = 0.0;                                 ///< largest radius [m]
  std::int64_t builds = 0;                            ///< number of builds so far
  /// The widest skin [m] (the adaptive skin's; 0: the skin): an active contact of the old list
  /// that the new one lacks has separated (it is no longer touching) and ends, unless it moved
  /// beyond r_i + r_j + skin_max, the numerical failure of a step too large for the packing.
  double skin_max = 0.0;
  std::int64_t built_at_step = 0;  ///< the Simulation's step count at the last build
  std::int64_t shell_pairs = 0;    ///< pairs of the last build not touching then (gap >= 0)
};

/// Re-map the cell to a less skewed cell of the same lattice when some |c_b . c_a| / |c_a|^2
/// exceeds max_skew (H <- H U, U unimodular), then wrap positions into the cell. Pair images are
/// updated so that every branch vector is unchanged. Returns true if H was re-mapped.
bool remap_and_wrap(Spheres& s, PeriodicCell& cell, Contacts& c, double max_skew);

/// New candidate pair list: all (i < j, k) with |x_j + H k - x_i| < r_i + r_j + skin, sorted by
/// (i, j, k). Contact history of active pairs of `old` is carried over; one the new list lacks is
/// not touching and ends, unless it is farther than r_i + r_j + max(skin, skin_max): then
/// NumericalError (a step too large for the packing). Builds the per-sphere lists. Throws
/// NumericalError if the cell is thinner than 2 r_max + skin.
void build_pairs(const Spheres& s, const PeriodicCell& cell, Contacts& c, VerletState& vs);

/// True when some pair not in the list may have come into contact since the last build.
[[nodiscard]] bool needs_rebuild(const Spheres& s, const PeriodicCell& cell, const VerletState& vs);

/// The parts of needs_rebuild, for a caller that runs the loop over spheres inside its own
/// parallel region: F = H H_ref^-1 (rebuild_deformation), |x_i - F x_ref,i|^2 of each sphere
/// (rebuild_drift2), then the measure of their maximum (rebuild_measure), which needs_rebuild
/// compares with vs.skin (a maximum is exact in any order).
/// @pre vs.x_ref.size() == s.size()
[[nodiscard]] inline common::Mat3 rebuild_deformation(const PeriodicCell& cell,
                                                      const VerletState& vs) {
  return cell.h * vs.h_ref_inv;
}
[[nodiscard]] inline double rebuild_drift2(const Spheres& s, const common::Mat3& f,
                                           const VerletState& vs, std::size_t i) {
  const double d2 = (s.x[i] - f * vs.x_ref[i]).squaredNorm();
  // A position that is not finite forces a rebuild, which names it (a NaN would drop out of the
  // maximum unnoticed).
  return d2 == d2 ? d2 : std::numeric_limits<double>::infinity();
}
/// The largest rebuild_drift2 over the spheres, on the calling thread.
[[nodiscard]] inline double max_drift2(const Spheres& s, const common::Mat3& f,
                                       const VerletState& vs) {
  double amax2 = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) amax2 = std::max(amax2, rebuild_drift2(s, f, vs, i));
  return amax2;
}
/// max_drift2 in a parallel region of its own (dem::one_thread: on the calling thread).
[[nodiscard]] double max_drift2_region(const Spheres& s, const common::Mat3& f,
                                       const VerletState& vs);
/// What a rebuild test compares with the skin: 2 max|a| + ||F - I||_F (2 r_max + skin) [m].
[[nodiscard]] double rebuild_measure(double amax2, const common::Mat3& f, double r_max,
                                     double skin);
/// rebuild_measure of the spheres' current positions (+inf without a list of them).
[[nodiscard]] double drift_measure(const Spheres& s, const PeriodicCell& cell,
                                   const VerletState& vs);

}  // namespace dem
