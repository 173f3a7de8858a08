// Drucker-Prager return mapping (see header).
#include "mpm/drucker_prager.hpp"

#include <cmath>

namespace mpm {

DruckerPragerResult drucker_prager_return(const common::Mat3& trial, double sin_phi) {
  DruckerPragerResult r;
  const common::Mat3 I = common::Mat3::Identity();
  const double p = -trial.trace() / 3.0;
  if (!(p > 0.0)) {
    r.stress = common::Mat3::Zero();
    r.plastic = true;
    r.apex = true;
    return r;
  }
  const common::Mat3 s = trial + p * I;  // deviator
  const double sqrt_j2 = std::sqrt(0.5 * (s.array() * s.array()).sum());
  const double limit = p * sin_phi;
  if (sqrt_j2 <= limit) {
    r.stress = trial;
    return r;
  }
  r.stress = s * (limit / sqrt_j2) - p * I;
  r.plastic = true;
  return r;
}

}  // namespace mpm
