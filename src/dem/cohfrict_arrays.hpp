// The properties of one contact and the history of every Verlet pair, one array per scalar field
// (structure of arrays): the batched contact law (CohFrictLaw::apply_batch) loads and stores lane
// q of a batch at pair first + q directly, without copying each contact in and out of the batch.
// Of the properties only the friction coefficient is stored per pair (Contacts::tan_phi); the
// stiffnesses and caps follow from the two radii and the material (CohFrictLaw::props).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "common/types.hpp"

namespace dem {

/// Properties of one contact: tan_phi is fixed when it is created (the friction angle may change
/// between creations); the others are functions of the radii and the material (cohfrict_stiffness).
struct ContactProps {
  double kn = 0.0;          ///< normal stiffness [N/m]
  double ks = 0.0;          ///< shear stiffness [N/m]
  double kr = 0.0;          ///< rolling stiffness [N m/rad]
  double kt = 0.0;          ///< twisting stiffness [N m/rad]
  double tan_phi = 0.0;     ///< Coulomb coefficient [-]
  double roll_cap = -1.0;   ///< eta_r min(R1, R2) [m]; < 0: no cap
  double twist_cap = -1.0;  ///< eta_t min(R1, R2) [m]; < 0: no cap
};

/// History of one contact, carried from step to step.
struct CohFrictHistory {
  common::Vec3 normal;  ///< unit normal from 1 to 2 of the previous step [-]
  common::Vec3 shear;   ///< shear force on sphere 2 [N]
  common::Vec3 roll;    ///< rolling moment on sphere 2 [N m]
  common::Vec3 twist;   ///< twisting moment on sphere 2 [N m]
};

/// CohFrictHistory of every pair, component by component (normal[a][p] is component a of the
/// normal of pair p). New entries are zero.
struct CohFrictHistoryArrays {
  std::array<std::vector<double>, 3> normal, shear, roll, twist;

  [[nodiscard]] std::size_t size() const { return normal[0].size(); }
  void resize(std::size_t n);
  [[nodiscard]] CohFrictHistory get(std::size_t p) const;
  void set(std::size_t p, const CohFrictHistory& h);
};

/// Entry p of a vector field stored component by component.
inline common::Vec3 at(const std::array<std::vector<double>, 3>& a, std::size_t p) {
  return {a[0][p], a[1][p], a[2][p]};
}

inline CohFrictHistory CohFrictHistoryArrays::get(std::size_t p) const {
  return {at(normal, p), at(shear, p), at(roll, p), at(twist, p)};
}

inline void CohFrictHistoryArrays::set(std::size_t p, const CohFrictHistory& h) {
  for (int a = 0; a < 3; ++a) {
    const auto k = static_cast<std::size_t>(a);
    normal[k][p] = h.normal[a];
    shear[k][p] = h.shear[a];
    roll[k][p] = h.roll[a];
    twist[k][p] = h.twist[a];
  }
}

}  // namespace dem
