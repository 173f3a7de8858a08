// Energy accounting of the MPM (see header).
#include "mpm/energy.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace mpm {

double Energies::ratio() const {
  if (kinetic == 0.0) return 0.0;
  if (!(internal_work > 0.0)) return std::numeric_limits<double>::infinity();
  return kinetic / internal_work;
}

double kinetic_energy(const MaterialPoints& points, double mass_scaling) {
  double sum = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) sum += points.mass[p] * points.v[p].squaredNorm();
  return 0.5 * mass_scaling * sum;
}

double stress_power(const MaterialPoints& points) {
  double sum = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const common::Mat3 D = 0.5 * (points.L[p] + points.L[p].transpose());
    sum += points.volume[p] * points.stress[p].cwiseProduct(D).sum();
  }
  return sum;
}

QuasiStaticWatch::QuasiStaticWatch(double threshold, double mass_scaling, double end_time)
    : threshold_(threshold), mass_scaling_(mass_scaling), start_(kWarmUp * end_time) {}

std::string QuasiStaticWatch::observe(std::int64_t step, double time, const Energies& e) {
  if (time < start_) return {};
  const double r = e.ratio();
  max_ratio_ = std::max(max_ratio_, r);
  if (warned_ || !(mass_scaling_ > 1.0) || !(r > threshold_)) return {};
  warned_ = true;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "mpm step %lld (t = %.6g s): the scene is no longer quasi-static: kinetic energy "
                "%.4g J is %.3g of the internal work %.4g J (mpm.quasi_static_ratio = %.3g) with "
                "mpm.mass_scaling = %.4g: lower the mass scaling or the loading rate",
                static_cast<long long>(step), time, e.kinetic, r, e.internal_work, threshold_,
                mass_scaling_);
  return buf;
}

}  // namespace mpm
