// Energy-growth guard (see header).
#include "mpm/energy_guard.hpp"

#include <algorithm>
#include <cmath>

namespace mpm {

void EnergyGuard::start(double kinetic, double internal_work) {
  started_ = true;
  kin0_ = kinetic;
  wint0_ = internal_work;
}

bool EnergyGuard::observe(double kinetic, double internal_work, double external_work_step) {
  w_ext_ += external_work_step;
  w_ext_abs_ += std::abs(external_work_step);
  const double dw_int = internal_work - wint0_;
  created_ = (kinetic - kin0_) + dw_int - w_ext_;
  scale_ = std::max({kinetic, kin0_, std::abs(dw_int), w_ext_abs_});
  if (!std::isfinite(created_)) return enabled();  // a blow-up past the doubles
  // The energy an unstable step creates is motion: a balance that drifts while the kinetic
  // energy stays small is an inconsistency of the materials' work, not a blow-up.
  const double s = scale_ > 0.0 && kinetic >= 0.5 * created_ ? created_ / scale_ : 0.0;
  const auto slot = static_cast<std::size_t>(observed_ % kPersist);
  last_share_[slot] = s;
  // The drift counts beyond kDriftSteps mean steps' work (scale / steps): a consistent step errs
  // by about one step's work, and in a run's first steps the scale is only a few of them (a
  // spared footing's first 27 steps held half of a 4e-4 J scale, then closed to -2 J of 40 J).
  const double steps = static_cast<double>(observed_ + 1);
  last_drift_[slot] =
      scale_ > 0.0 && created_ * steps > kDriftSteps * scale_ ? created_ / scale_ : 0.0;
  last_kin_[slot] = kinetic;
  ++observed_;
  if (observed_ < kPersist) return false;
  const double held = *std::min_element(last_share_.begin(), last_share_.end());
  max_share_ = std::max(max_share_, held);
  drift_ = *std::min_element(last_drift_.begin(), last_drift_.end());
  max_drift_ = std::max(max_drift_, drift_);
  // The oldest of the kPersist steps is the next slot of the ring.
  const double kin_first = last_kin_[static_cast<std::size_t>(observed_ % kPersist)];
  return enabled() && held > share_ && kinetic > kin_first;
}

}  // namespace mpm
