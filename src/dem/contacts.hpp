// Verlet pairs and contact history as structure-of-arrays. A pair (i < j, image k) is a candidate;
// it is an active contact while the spheres overlap. Pairs are sorted by (i, j, k): deterministic.
#pragma once

#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "dem/contact_law_cohfrict.hpp"

namespace dem {

struct Contacts {
  // Pair identity (from the neighbour search).
  std::vector<std::int32_t> i, j;  ///< sphere ids, i < j
  std::vector<common::Vec3i> k;    ///< image: branch = x_j + H k - x_i
  // Contact state.
  std::vector<std::uint8_t> active;   ///< 1 while in overlap
  std::vector<CohFrictProps> props;   ///< fixed at creation
  std::vector<CohFrictHistory> hist;  ///< normal, shear force, rolling and twisting moments
  // Output of the last force computation (zero for inactive pairs).
  std::vector<common::Vec3> force;               ///< force on j [N]
  std::vector<common::Vec3> torque_i, torque_j;  ///< [N m]
  std::vector<common::Vec3> branch;              ///< branch vector of the last step [m]
  std::vector<double> fn;                        ///< normal force magnitude [N]

  // Per-sphere list of pairs (CSR), in pair order: sphere s touches pairs
  // sphere_pairs[sphere_offset[s] .. sphere_offset[s+1]); a negative entry -p-1 means s == j of p.
  std::vector<std::int64_t> sphere_offset;
  std::vector<std::int64_t> sphere_pairs;

  [[nodiscard]] std::size_t size() const { return i.size(); }
  void resize(std::size_t n);
  /// Build the per-sphere CSR for n_spheres spheres.
  void build_sphere_lists(std::size_t n_spheres);
};

}  // namespace dem
