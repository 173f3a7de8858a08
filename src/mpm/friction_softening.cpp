// Friction softening of the Drucker-Prager cone (see header).
#include "mpm/friction_softening.hpp"

#include <algorithm>
#include <cmath>

namespace mpm {

double FrictionSoftening::eta(double gamma) const {
  return eta_peak - (eta_peak - eta_residual) * std::min(1.0, gamma / strain);
}

SofteningResult softening_return(const common::Mat3& trial, const FrictionSoftening& softening,
                                 double gamma0, double shear) {
  SofteningResult out;
  out.gamma = gamma0;
  const double eta0 = softening.eta(gamma0);
  const common::Mat3 I = common::Mat3::Identity();
  const double p = -trial.trace() / 3.0;
  if (!(p > 0.0)) {
    out.result.stress = common::Mat3::Zero();
    out.result.plastic = true;
    out.result.apex = true;
    return out;
  }
  const common::Mat3 s = trial + p * I;  // deviator
  const double sqrt_j2 = std::sqrt(0.5 * (s.array() * s.array()).sum());
  if (sqrt_j2 <= eta0 * p) {
    out.result.stress = trial;
    return out;
  }
  double limit = 0.0;  // sqrt(J2) after the return
  const double k = gamma0 < softening.strain
                       ? (softening.eta_peak - softening.eta_residual) / softening.strain
                       : 0.0;
  const double denominator = shear - k * p;
  const double dgamma_softening = denominator > 0.0 ? (sqrt_j2 - eta0 * p) / denominator : 0.0;
  if (k == 0.0) {  // on the residual cone (or no softening): the perfectly plastic return
    limit = eta0 * p;
    out.gamma = gamma0 + (sqrt_j2 - limit) / shear;
  } else if (denominator > 0.0 && gamma0 + dgamma_softening <= softening.strain) {
    limit = (eta0 - k * dgamma_softening) * p;
    out.gamma = gamma0 + dgamma_softening;
  } else {  // past the residual strain within the step, or a snap-back: the residual cone
    limit = softening.eta_residual * p;
    out.gamma = std::max(gamma0 + (sqrt_j2 - limit) / shear, softening.strain);
  }
  out.result.stress = s * (limit / sqrt_j2) - p * I;
  out.result.plastic = true;
  return out;
}

}  // namespace mpm
