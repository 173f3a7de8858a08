// Uniform GIMP (uGIMP) shape function: the linear hat averaged over the point's undeformed
// box domain. Bardenhagen & Kober 2004, CMES 5(6), 477-495, doi:10.3970/cmes.2004.005.477.
#pragma once

#include <cmath>

namespace mpm {

/// 1D uGIMP in cell units: r = (x_p - x_i) / h, lp = domain half-width / h in (0, 1/2].
/// Stateless; the 3D function is the tensor product over the three axes (box domains).
struct UgimpShape {
  static constexpr int support = 3;
  /// Lowest node index with |r| < 1 + lp: floor(s - lp).
  static int stencil_base(double s, double lp) { return static_cast<int>(std::floor(s - lp)); }
  /// S(r) [-].
  static double value(double r, double lp) {
    const double a = std::abs(r);
    if (lp <= 0.0) return a < 1.0 ? 1.0 - a : 0.0;
    if (a < lp) return 1.0 - (r * r + lp * lp) / (2.0 * lp);
    if (a < 1.0 - lp) return 1.0 - a;
    if (a < 1.0 + lp) {
      const double b = 1.0 + lp - a;
      return b * b / (4.0 * lp);
    }
    return 0.0;
  }
  /// dS/dr [-] (divide by h for dS/dx).
  static double gradient(double r, double lp) {
    const double a = std::abs(r);
    const double sign = r >= 0.0 ? 1.0 : -1.0;
    if (lp <= 0.0) return (r < 1.0 && r >= -1.0) ? -sign : 0.0;  // linear, right-hand at kinks
    if (a < lp) return -r / lp;
    if (a < 1.0 - lp) return -sign;
    if (a < 1.0 + lp) return -sign * (1.0 + lp - a) / (2.0 * lp);
    return 0.0;
  }
};

}  // namespace mpm
