// Cell-averaged velocity gradient, whole or its trace (see strain_smoothing.hpp,
// docs/design/mpm.md "Strain smoothing").
#include "mpm/strain_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace mpm {

StrainSmoothing strain_smoothing_from_string(std::string_view name) {
  if (const auto s = common::value_of(kStrainSmoothingNames, name)) return *s;
  throw common::InputError("mpm.strain_smoothing = \"" + std::string(name) + "\": must be one of " +
                           common::names_list(kStrainSmoothingNames));
}

std::string_view to_string(StrainSmoothing s) { return common::name_of(kStrainSmoothingNames, s); }

std::int64_t cell_of(const Grid& grid, const common::Vec3& x) {
  std::int64_t ijk[3] = {0, 0, 0};
  for (int d = 0; d < 3; ++d) {
    const double c = std::floor((x[d] - grid.origin[d]) / grid.spacing[d]);
    ijk[d] = std::clamp(static_cast<std::int64_t>(c), std::int64_t{0},
                        static_cast<std::int64_t>(grid.cells[d]) - 1);
  }
  return ijk[0] + grid.cells[0] * (ijk[1] + grid.cells[1] * ijk[2]);
}

void average_per_cell(const Grid& grid, const std::vector<common::Vec3>& x,
                      const std::vector<double>& volume, std::vector<common::Mat3>& L,
                      std::vector<std::pair<std::int64_t, std::int64_t>>& scratch) {
  if (volume.size() != x.size() || L.size() != x.size()) {
    throw common::NumericalError("average_per_cell: x, volume and L differ in size");
  }
  for_each_cell(grid, x, scratch, [&](std::size_t begin, std::size_t end) {
    common::Mat3 sum = common::Mat3::Zero();
    double v = 0.0;
    for (std::size_t k = begin; k < end; ++k) {
      const auto p = static_cast<std::size_t>(scratch[k].second);
      sum += volume[p] * L[p];
      v += volume[p];
    }
    const common::Mat3 mean = sum / v;
    for (std::size_t k = begin; k < end; ++k) L[static_cast<std::size_t>(scratch[k].second)] = mean;
  });
}

void average_trace_per_cell(const Grid& grid, const std::vector<common::Vec3>& x,
                            const std::vector<double>& volume, int thickness_axis,
                            std::vector<common::Mat3>& T,
                            std::vector<std::pair<std::int64_t, std::int64_t>>& scratch) {
  if (volume.size() != x.size() || T.size() != x.size()) {
    throw common::NumericalError("average_trace_per_cell: x, volume and T differ in size");
  }
  const int axes = thickness_axis >= 0 ? 2 : 3;
  auto trace = [&](const common::Mat3& m) {
    double t = 0.0;
    for (int d = 0; d < 3; ++d) {
      if (d != thickness_axis) t += m(d, d);
    }
    return t;
  };
  for_each_cell(grid, x, scratch, [&](std::size_t begin, std::size_t end) {
    double sum = 0.0;
    double v = 0.0;
    for (std::size_t k = begin; k < end; ++k) {
      const auto p = static_cast<std::size_t>(scratch[k].second);
      sum += volume[p] * trace(T[p]);
      v += volume[p];
    }
    const double mean = sum / v;
    for (std::size_t k = begin; k < end; ++k) {
      common::Mat3& m = T[static_cast<std::size_t>(scratch[k].second)];
      const double shift = (mean - trace(m)) / axes;
      for (int d = 0; d < 3; ++d) {
        if (d != thickness_axis) m(d, d) += shift;
      }
    }
  });
}

}  // namespace mpm
