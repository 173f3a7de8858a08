// Energy accounting of the MPM for quasi-static scenes (docs/design/mpm.md, "Mass scaling"): kinetic
// energy of the points with the scaled inertia, the stress power, the kinetic-to-internal ratio,
// and a watch that warns once when a mass-scaled scene stops being quasi-static.
#pragma once

#include <cstdint>
#include <string>

#include "mpm/material_points.hpp"

namespace mpm {

/// The energies a run reports.
struct Energies {
  double kinetic = 0.0;  ///< 1/2 s sum_p m_p |v_p|^2 with the mass scaling s [J]
  /// Internal work since the start: the sum over steps of dt times the stress power
  /// (stress_power) [J]; positive when a body is compressed against a compressive stress.
  double internal_work = 0.0;
  /// kinetic / internal_work [-]; 0 when both are 0, +inf when only the internal work is <= 0.
  [[nodiscard]] double ratio() const;
};

/// 1/2 s sum_p m_p |v_p|^2 [J] (s: the mass scaling, 1 = off). Sums in slot order.
[[nodiscard]] double kinetic_energy(const MaterialPoints& points, double mass_scaling);

/// sum_p V_p sigma_p : D_p [W], D_p = (L_p + L_p^T) / 2, with the points' current volume, stress
/// (tension positive) and L: the rate of work of the stresses on the material (positive when a
/// compressed body is compressed further: sigma and D both negative). Sums in slot order.
[[nodiscard]] double stress_power(const MaterialPoints& points);

/// Watches the kinetic-to-internal energy ratio of a mass-scaled run. The start of any loading
/// from rest is dynamic (from rest at a constant platen speed the ratio falls like 1 / t), so
/// the ratio is watched from kWarmUp of the end time on.
class QuasiStaticWatch {
 public:
  static constexpr double kWarmUp = 0.05;  ///< share of the end time not watched [-]
  /// threshold: SolverConfig::quasi_static_ratio; no warning when mass_scaling <= 1.
  QuasiStaticWatch(double threshold, double mass_scaling, double end_time);
  /// Call after each step: the warning text the first time the ratio exceeds the threshold
  /// after the warm-up (with the step, the time, the ratio and the threshold); "" otherwise.
  [[nodiscard]] std::string observe(std::int64_t step, double time, const Energies& e);
  /// Largest ratio observed after the warm-up (0 before) [-].
  [[nodiscard]] double max_ratio() const { return max_ratio_; }
  [[nodiscard]] bool warned() const { return warned_; }

 private:
  double threshold_;
  double mass_scaling_;
  double start_;
  double max_ratio_ = 0.0;
  bool warned_ = false;
};

}  // namespace mpm
