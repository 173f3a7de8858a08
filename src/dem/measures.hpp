// State measurements of a periodic packing: Love-Weber stress invariants, fabric, coordination
// (with and without rattlers), void ratio, unbalanced force, kinetic energy.
#pragma once

#include "common/tensor.hpp"
#include "common/types.hpp"
#include "dem/simulation.hpp"

namespace dem {

// p = -tr(sigma)/3 and q = sqrt(3/2 s:s) (for a triaxial state |sigma_a - sigma_r|): one home.
using common::deviatoric;
using common::pressure;

struct Measures {
  common::Mat3 stress = common::Mat3::Zero();  ///< Love-Weber, tension positive [Pa]
  double p = 0.0;                              ///< -tr(sigma)/3 [Pa]
  double q = 0.0;                              ///< sqrt(3/2 s:s) [Pa]
  common::Mat3 fabric = common::Mat3::Zero();  ///< <n (x) n> over contacts [-]
  double z = 0.0;                              ///< 2 Nc / N [-]
  double z_mech = 0.0;  ///< 2 Nc' / N' without rattlers (spheres with < 2 contacts, iterated) [-]
  double void_ratio = 0.0;  ///< V / V_solid - 1 [-]
  double unbalanced = 0.0;  ///< mean |f_sphere| / mean |f_contact| [-]
  double kinetic = 0.0;     ///< fluctuating kinetic energy 1/2 (m u^2 + I w^2) [J]
  std::int64_t n_contacts = 0;
};

/// Measure the current state (from the last force computation), fixed-order sums.
[[nodiscard]] Measures measure(const Simulation& sim);

/// Void ratio only (cheap) [-].
[[nodiscard]] double void_ratio(const Simulation& sim);

}  // namespace dem
