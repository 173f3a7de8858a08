// Linear (tent) shape function of classical MPM, the one of Duverger et al. 2022 (eq. 3).
#pragma once

#include <cmath>

namespace mpm {

/// 1D linear hat, in cell units: r = (x_p - x_i) / h, value 1 - |r| on |r| < 1.
/// Stateless; the 3D function is the tensor product over the three axes.
struct LinearShape {
  /// Nodes per axis in a point's stencil.
  static constexpr int support = 2;
  /// Lowest node index (per axis) of the stencil of a point at s = (x_p - origin) / h;
  /// half_width (domain half-width / h) is unused.
  static int stencil_base(double s, double /*half_width*/) {
    return static_cast<int>(std::floor(s));
  }
  /// S(r) [-].
  static double value(double r, double /*half_width*/) {
    const double a = std::abs(r);
    return a < 1.0 ? 1.0 - a : 0.0;
  }
  /// dS/dr [-] (divide by h for dS/dx); at the kinks r = -1, 0 the right-hand derivative (the
  /// one of the point's cell), so that the gradients of a stencil sum to zero.
  static double gradient(double r, double /*half_width*/) {
    if (r >= 1.0 || r < -1.0) return 0.0;
    return r >= 0.0 ? -1.0 : 1.0;
  }
};

}  // namespace mpm
