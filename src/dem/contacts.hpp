// Verlet pairs and contact history as structure-of-arrays. A pair (i < j, image k) is a candidate;
// it is an active contact while the spheres overlap. Pairs are sorted by (i, j, k): deterministic.
#pragma once

#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "dem/cohfrict_arrays.hpp"

namespace dem {

struct Contacts {
  // Pair identity (from the neighbour search).
  std::vector<std::int32_t> i, j;  ///< sphere ids, i < j
  std::vector<common::Vec3i> k;    ///< image: branch = x_j + H k - x_i
  // Contact state.
  std::vector<std::uint8_t> active;  ///< 1 while in overlap
  /// Coulomb coefficient tan(phi) of the contact, fixed when it is created (the friction angle
  /// may change between creations); 0 for a pair never in contact. The other properties follow
  /// from the radii (Simulation::contact_props).
  std::vector<double> tan_phi;
  CohFrictHistoryArrays hist;  ///< normal, shear force, rolling and twisting moments (hist.get(p))
  // Output of the last force computation (zero for inactive pairs).
  std::vector<common::Vec3> force;               ///< force on j [N]
  std::vector<common::Vec3> torque_i, torque_j;  ///< [N m]
  /// Branch x_j + H k - x_i of the last force computation, of every pair (in contact or not) [m].
  std::vector<common::Vec3> branch;
  // The normal force magnitude kn (r_i + r_j - |branch|) is not stored: Simulation::normal_force.

  // Per-sphere list of pairs (CSR), in pair order: sphere s touches pairs
  // sphere_pairs[sphere_offset[s] .. sphere_offset[s+1]); a negative entry -p-1 means s == j of p.
  std::vector<std::int64_t> sphere_offset;
  std::vector<std::int32_t> sphere_pairs;  ///< 4 bytes: read twice per pair and step

  /// Whether some pair may twist: unknown until looked at (resize makes it unknown), none when
  /// every twisting moment is zero (the law then skips its twisting part while the material has
  /// no twisting stiffness: Simulation sets some when it has), some otherwise. Whoever writes a
  /// non-zero twist into the arrays other than through resize must set it to some (or unknown).
  enum class Twist : std::uint8_t { unknown, none, some };
  Twist twist = Twist::unknown;

  [[nodiscard]] std::size_t size() const { return i.size(); }
  void resize(std::size_t n);
  /// Resolves twist = unknown by looking at every pair.
  void classify_twist();
  /// Build the per-sphere CSR for n_spheres spheres.
  void build_sphere_lists(std::size_t n_spheres);
};

}  // namespace dem
