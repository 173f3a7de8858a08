// Sub-cell stress relaxation (see subcell_relaxation.hpp).
#include "mpm/subcell_relaxation.hpp"

#include "common/errors.hpp"
#include "mpm/strain_smoothing.hpp"

namespace mpm {

void relax_subcell_stress(const Grid& grid, const std::vector<common::Vec3>& x,
                          const std::vector<double>& mass, const std::vector<double>& volume,
                          const std::vector<common::Mat3>& stress, int thickness_axis, double c,
                          double tau, std::vector<common::Mat3>& L,
                          std::vector<std::pair<std::int64_t, std::int64_t>>& scratch) {
  const std::size_t n = x.size();
  if (mass.size() != n || volume.size() != n || stress.size() != n || L.size() != n) {
    throw common::NumericalError("relax_subcell_stress: the point arrays differ in size");
  }
  if (!(c > 0.0) || !(tau > 0.0)) {
    throw common::NumericalError("relax_subcell_stress: needs a positive wave speed and time");
  }
  for_each_cell(grid, x, scratch, [&](std::size_t begin, std::size_t end) {
    if (end - begin < 2) return;
    common::Mat3 sum = common::Mat3::Zero();
    double v = 0.0;
    double m = 0.0;
    for (std::size_t k = begin; k < end; ++k) {
      const auto p = static_cast<std::size_t>(scratch[k].second);
      sum += volume[p] * stress[p];
      v += volume[p];
      m += mass[p];
    }
    const common::Mat3 mean = sum / v;
    const double rate = 1.0 / ((m / v) * c * c * tau);  // 1 / (rho c^2 tau) [1/(Pa s)]
    for (std::size_t k = begin; k < end; ++k) {
      const auto p = static_cast<std::size_t>(scratch[k].second);
      common::Mat3 d = -rate * (stress[p] - mean);
      if (thickness_axis >= 0) {
        d.row(thickness_axis).setZero();
        d.col(thickness_axis).setZero();
      }
      L[p] += d;
    }
  });
}

}  // namespace mpm
