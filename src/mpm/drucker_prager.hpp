// Cohesionless Drucker-Prager plasticity, with or without dilatancy: the yield surface of a
// frictional continuum (a reference for the DEM RVEs, never a replacement for them).
#pragma once

#include "common/types.hpp"

namespace mpm {

/// What one return mapping did.
struct DruckerPragerResult {
  common::Mat3 stress;   ///< Cauchy stress after the return, tension positive [Pa]
  bool plastic = false;  ///< the trial stress lay outside the cone
  bool apex = false;     ///< the trial stress returned to the apex, zero stress
};

/// A cohesionless Drucker-Prager cone sqrt(J2) <= eta p (p = -tr(sigma)/3) with the plastic
/// potential sqrt(J2) - eta_bar p: eta_bar = 0 is a deviatoric flow (no dilatancy), eta_bar = eta
/// an associated one.
struct DruckerPragerCone {
  double eta = 0.0;      ///< slope of the yield surface [-]
  double eta_bar = 0.0;  ///< slope of the plastic potential (dilatancy) [-], in [0, eta]
};

/// The cone that coincides with Mohr-Coulomb (friction angle phi, dilatancy angle psi) in plane
/// strain at plastic flow. The plane-strain condition on the plastic strain fixes the out-of-plane
/// deviator, s_yy = 2 eta_bar sqrt(J2) / 3 (compression positive); then (sigma_1 - sigma_3) /
/// (sigma_1 + sigma_3) = sin(phi) and -tr(d eps_p) / (d eps_1 - d eps_3) = sin(psi) give
///   eta_bar = 3 sin(psi) / sqrt(9 + 3 sin^2(psi)),
///   eta = sin(phi) / (sqrt(1 - eta_bar^2 / 3) + sin(phi) eta_bar / 3)
/// (psi = 0: eta = sin(phi); psi = phi: eta = eta_bar = 3 sin(phi) / sqrt(9 + 3 sin^2(phi)), the
/// associated plane-strain match of de Souza Neto, Peric & Owen 2008, section 6.4.2).
/// @param phi friction angle [rad], in [0, pi/2)
/// @param psi dilatancy angle [rad], in [0, phi]
[[nodiscard]] DruckerPragerCone plane_strain_cone(double phi, double psi);

/// Return mapping of a trial stress (tension positive) onto the cone sqrt(J2) <= p sin(phi), with
/// a deviatoric flow (dilatancy angle 0): the return keeps p and scales the deviator radially. A
/// trial stress with p <= 0 returns to the apex, zero stress: a cohesionless material carries no
/// tension (it is disconnected).
/// @param sin_phi sine of the friction angle, in [0, 1)
[[nodiscard]] DruckerPragerResult drucker_prager_return(const common::Mat3& trial, double sin_phi);

/// Return mapping onto a cone with a dilatant flow, for an isotropic linear elastic material of
/// bulk modulus K and shear modulus G: the plastic multiplier
///   dgamma = (sqrt(J2_trial) - eta p_trial) / (G + K eta eta_bar)
/// scales the deviator by 1 - G dgamma / sqrt(J2_trial) and raises p by K eta_bar dgamma (the
/// plastic dilation unloads the elastic volume strain: under a constrained volume a dilatant
/// material's pressure grows). The apex (zero stress) takes the trial stresses with
/// G p_trial + K eta_bar sqrt(J2_trial) <= 0, whose return would pass it. With eta_bar = 0 the
/// result is bit for bit that of drucker_prager_return(trial, eta).
[[nodiscard]] DruckerPragerResult drucker_prager_return(const common::Mat3& trial,
                                                        const DruckerPragerCone& cone, double bulk,
                                                        double shear);

}  // namespace mpm
