// Friction softening of the cohesionless Drucker-Prager cone: a frictional continuum whose
// friction falls from a peak to a residual value with the plastic shear strain, the simplest
// material that softens (docs/design/mpm.md, "Frictional continuum"). A reference for the
// regularisation's mesh studies, never a model of the RVEs.
#pragma once

#include "mpm/drucker_prager.hpp"

namespace mpm {

/// The cone's slope eta = sin(phi) falls linearly with the accumulated plastic shear strain
/// gamma from sin(phi_peak) to sin(phi_residual), reached at gamma = strain, then stays there:
///   eta(gamma) = eta_peak - (eta_peak - eta_residual) min(1, gamma / strain).
/// The flow is deviatoric (no dilatancy), and eta = sin(phi) is the plane-strain Mohr-Coulomb
/// match of such a flow (plane_strain_cone(phi, 0)).
struct FrictionSoftening {
  double eta_peak = 0.0;      ///< sin(phi_peak) [-], in [0, 1)
  double eta_residual = 0.0;  ///< sin(phi_residual) [-], in [0, eta_peak]
  double strain = 0.0;        ///< gamma at which the residual is reached [-], > 0
  /// The slope at the accumulated plastic shear strain gamma >= 0.
  [[nodiscard]] double eta(double gamma) const;
};

/// What one softening return did.
struct SofteningResult {
  DruckerPragerResult result;
  double gamma = 0.0;  ///< the accumulated plastic shear strain after the return [-]
};

/// Return mapping of a trial stress (tension positive) of an isotropic elastic material of shear
/// modulus G onto the softening cone, starting from the accumulated plastic shear strain gamma0.
/// The plastic shear strain increment is dgamma = (sqrt(J2_trial) - sqrt(J2)) / G (in simple
/// shear, the plastic part of the engineering shear strain), and the return is implicit: the
/// final stress lies on the cone of the final gamma,
///   sqrt(J2_trial) - G dgamma = eta(gamma0 + dgamma) p,
/// so on the softening branch dgamma = (sqrt(J2_trial) - eta(gamma0) p) / (G - k p), k = (eta_peak
/// - eta_residual) / strain. Where that return would pass gamma = strain it is made onto the
/// residual cone instead; where G <= k p (a softening faster than the elastic unloading: the point
/// snaps back) the stress drops to the residual cone at once and gamma to at least strain. A
/// trial stress with p <= 0 returns to the apex (zero stress, gamma unchanged). With eta_peak =
/// eta_residual the stress is bit for bit that of drucker_prager_return(trial, eta_peak).
[[nodiscard]] SofteningResult softening_return(const common::Mat3& trial,
                                               const FrictionSoftening& softening, double gamma0,
                                               double shear);

}  // namespace mpm
