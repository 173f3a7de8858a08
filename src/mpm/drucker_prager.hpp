// Cohesionless Drucker-Prager plasticity without dilatancy: the yield surface of a frictional
// continuum (a reference for the DEM RVEs, never a replacement for them).
#pragma once

#include "common/types.hpp"

namespace mpm {

/// What one return mapping did.
struct DruckerPragerResult {
  common::Mat3 stress;   ///< Cauchy stress after the return, tension positive [Pa]
  bool plastic = false;  ///< the trial stress lay outside the cone
  bool apex = false;     ///< the trial mean stress was tensile: returned to zero stress
};

/// Return mapping of a trial stress (tension positive) onto the cone sqrt(J2) <= p sin(phi),
/// p = -tr(sigma)/3. This is the Drucker-Prager cone that coincides with Mohr-Coulomb in plane
/// strain when the flow has no dilatancy (then s_yy = 0 at yield, sqrt(J2) = (sigma_1 -
/// sigma_3)/2 and p = (sigma_1 + sigma_3)/2). The flow is deviatoric (dilatancy angle 0), so the
/// return keeps p and scales the deviator radially. A trial stress with p <= 0 returns to the
/// apex, zero stress: a cohesionless material carries no tension (it is disconnected).
/// @param sin_phi sine of the friction angle, in [0, 1)
[[nodiscard]] DruckerPragerResult drucker_prager_return(const common::Mat3& trial, double sin_phi);

}  // namespace mpm
