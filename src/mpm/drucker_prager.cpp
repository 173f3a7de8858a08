// Drucker-Prager return mapping (see header).
#include "mpm/drucker_prager.hpp"

#include <cmath>

namespace mpm {

DruckerPragerCone plane_strain_cone(double phi, double psi) {
  const double sin_phi = std::sin(phi);
  if (psi == 0.0) return {sin_phi, 0.0};
  const double sin_psi = std::sin(psi);
  DruckerPragerCone c;
  c.eta_bar = 3.0 * sin_psi / std::sqrt(9.0 + 3.0 * sin_psi * sin_psi);
  c.eta = sin_phi / (std::sqrt(1.0 - c.eta_bar * c.eta_bar / 3.0) + sin_phi * c.eta_bar / 3.0);
  return c;
}

DruckerPragerResult drucker_prager_return(const common::Mat3& trial, double sin_phi) {
  return drucker_prager_return(trial, DruckerPragerCone{sin_phi, 0.0}, 0.0, 0.0);
}

DruckerPragerResult drucker_prager_return(const common::Mat3& trial, const DruckerPragerCone& cone,
                                          double bulk, double shear) {
  DruckerPragerResult r;
  const common::Mat3 I = common::Mat3::Identity();
  const double p = -trial.trace() / 3.0;
  const common::Mat3 s = trial + p * I;  // deviator
  const double sqrt_j2 = std::sqrt(0.5 * (s.array() * s.array()).sum());
  const bool dilatant = cone.eta_bar > 0.0;
  const bool apex = dilatant ? !(shear * p + bulk * cone.eta_bar * sqrt_j2 > 0.0) : !(p > 0.0);
  if (apex) {
    r.stress = common::Mat3::Zero();
    r.plastic = true;
    r.apex = true;
    return r;
  }
  if (sqrt_j2 <= cone.eta * p) {
    r.stress = trial;
    return r;
  }
  double p_new = p;
  if (dilatant) {
    const double dgamma = (sqrt_j2 - cone.eta * p) / (shear + bulk * cone.eta * cone.eta_bar);
    p_new = p + bulk * cone.eta_bar * dgamma;
  }
  const double limit = p_new * cone.eta;  // sqrt(J2) after the return
  r.stress = s * (limit / sqrt_j2) - p_new * I;
  r.plastic = true;
  return r;
}

}  // namespace mpm
