// Quadratic B-spline shape function (C1, non-interpolating). Steffen, Kirby & Berzins 2008,
// IJNME 76(6), 922-948, doi:10.1002/nme.2360.
#pragma once

#include <cmath>

namespace mpm {

/// 1D uniform quadratic B-spline centred on the node, in cell units r = (x_p - x_i) / h:
/// 3/4 - r^2 on |r| < 1/2, (3/2 - |r|)^2 / 2 on 1/2 <= |r| < 3/2. Stateless; tensor product in 3D.
/// It is a partition of unity only where all three stencil nodes exist: the grid needs one
/// layer of cells around the material.
struct BSpline2Shape {
  static constexpr int support = 3;
  static int stencil_base(double s, double /*half_width*/) {
    return static_cast<int>(std::floor(s - 0.5));
  }
  static double value(double r, double /*half_width*/) {
    const double a = std::abs(r);
    if (a < 0.5) return 0.75 - r * r;
    if (a < 1.5) {
      const double b = 1.5 - a;
      return 0.5 * b * b;
    }
    return 0.0;
  }
  /// dS/dr [-] (divide by h for dS/dx).
  static double gradient(double r, double /*half_width*/) {
    const double a = std::abs(r);
    if (a < 0.5) return -2.0 * r;
    if (a < 1.5) return (r >= 0.0 ? -1.0 : 1.0) * (1.5 - a);
    return 0.0;
  }
};

}  // namespace mpm
