// Cell-averaged velocity gradient (see strain_smoothing.hpp, docs/design/mpm.md "Strain
// smoothing").
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
  const std::size_t n = x.size();
  if (volume.size() != n || L.size() != n) {
    throw common::NumericalError("average_per_cell: x, volume and L differ in size");
  }
  // (cell, point) pairs sorted by cell then point: each cell's points in point order.
  scratch.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    scratch[p] = {cell_of(grid, x[p]), static_cast<std::int64_t>(p)};
  }
  std::sort(scratch.begin(), scratch.end());
  for (std::size_t begin = 0; begin < n;) {
    std::size_t end = begin;
    common::Mat3 sum = common::Mat3::Zero();
    double v = 0.0;
    for (; end < n && scratch[end].first == scratch[begin].first; ++end) {
      const auto p = static_cast<std::size_t>(scratch[end].second);
      sum += volume[p] * L[p];
      v += volume[p];
    }
    const common::Mat3 mean = sum / v;
    for (std::size_t k = begin; k < end; ++k) L[static_cast<std::size_t>(scratch[k].second)] = mean;
    begin = end;
  }
}

}  // namespace mpm
