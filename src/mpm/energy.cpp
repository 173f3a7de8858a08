// Energy accounting of the MPM (see header).
#include "mpm/energy.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

#include "mpm/parallel.hpp"

namespace mpm {

double Energies::ratio() const {
  if (kinetic == 0.0) return 0.0;
  if (!(internal_work > 0.0)) return std::numeric_limits<double>::infinity();
  return kinetic / internal_work;
}

// The terms in parallel, added in slot order: the same bits as a serial loop on any number of
// threads (the sums themselves are a small part of the cost).
double kinetic_energy(const MaterialPoints& points, double mass_scaling) {
  thread_local std::vector<double> terms;
  compute_terms(static_cast<std::int64_t>(points.size()), terms, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    return points.mass[p] * points.v[p].squaredNorm();
  });
  double sum = 0.0;
  for (const double t : terms) sum += t;
  return 0.5 * mass_scaling * sum;
}

double stress_power(const MaterialPoints& points) {
  thread_local std::vector<double> terms;
  compute_terms(static_cast<std::int64_t>(points.size()), terms, [&](std::int64_t q) {
    const auto p = static_cast<std::size_t>(q);
    const common::Mat3 D = 0.5 * (points.L[p] + points.L[p].transpose());
    return points.volume[p] * points.stress[p].cwiseProduct(D).sum();
  });
  double sum = 0.0;
  for (const double t : terms) sum += t;
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
