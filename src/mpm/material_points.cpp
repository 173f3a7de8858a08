// Material point storage: append, resize, validation, regular filling of a box.
#include "mpm/material_points.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "common/errors.hpp"

namespace mpm {

void MaterialPoints::add(std::int64_t point_id, const common::Vec3& position, double point_mass,
                         double point_volume, const common::Vec3& half_width,
                         std::int32_t material_id) {
  id.push_back(point_id);
  x.push_back(position);
  v.push_back(common::Vec3::Zero());
  mass.push_back(point_mass);
  volume.push_back(point_volume);
  volume0.push_back(point_volume);
  half_width0.push_back(half_width);
  stress.push_back(common::Mat3::Zero());
  F.push_back(common::Mat3::Identity());
  L.push_back(common::Mat3::Zero());
  C.push_back(common::Mat3::Zero());
  material.push_back(material_id);
}

void MaterialPoints::resize(std::size_t n) {
  id.resize(n, 0);
  x.resize(n, common::Vec3::Zero());
  v.resize(n, common::Vec3::Zero());
  mass.resize(n, 0.0);
  volume.resize(n, 0.0);
  volume0.resize(n, 0.0);
  half_width0.resize(n, common::Vec3::Zero());
  stress.resize(n, common::Mat3::Zero());
  F.resize(n, common::Mat3::Identity());
  L.resize(n, common::Mat3::Zero());
  C.resize(n, common::Mat3::Zero());
  material.resize(n, 0);
}

void MaterialPoints::validate() const {
  const std::size_t n = x.size();
  if (id.size() != n || v.size() != n || mass.size() != n || volume.size() != n ||
      volume0.size() != n || half_width0.size() != n || stress.size() != n || F.size() != n ||
      L.size() != n || C.size() != n || material.size() != n) {
    throw common::InputError("mpm points: the per-point arrays have different sizes");
  }
  std::set<std::int64_t> seen;
  for (std::size_t p = 0; p < n; ++p) {
    const std::string where = "mpm points: point id " + std::to_string(id[p]);
    if (!seen.insert(id[p]).second) throw common::InputError(where + ": id is not unique");
    if (!(mass[p] > 0.0)) throw common::InputError(where + ": mass must be > 0 kg");
    if (!(volume[p] > 0.0) || !(volume0[p] > 0.0)) {
      throw common::InputError(where + ": volume must be > 0 m^3");
    }
    if (!(half_width0[p].minCoeff() > 0.0)) {
      throw common::InputError(where + ": half-widths must be > 0 m");
    }
    if (material[p] < 0) throw common::InputError(where + ": material index must be >= 0");
  }
}

std::size_t fill_box(MaterialPoints& points, const Grid& grid, const common::Vec3& lo,
                     const common::Vec3& hi, const common::Vec3i& points_per_cell, double density,
                     std::int32_t material_id) {
  for (int d = 0; d < 3; ++d) {
    if (points_per_cell[d] < 1) {
      throw common::InputError("mpm fill_box: points_per_cell along axis " + std::to_string(d) +
                               " = " + std::to_string(points_per_cell[d]) + ": must be >= 1");
    }
  }
  if (!(density > 0.0)) {
    throw common::InputError("mpm fill_box: density = " + std::to_string(density) +
                             ": must be > 0 kg/m^3");
  }
  common::Vec3i n;
  for (int d = 0; d < 3; ++d) {
    const double cells = (hi[d] - lo[d]) / grid.spacing[d];
    n[d] = static_cast<int>(std::lround(cells)) * points_per_cell[d];
    if (n[d] < 1 || std::abs(cells - std::round(cells)) > 1e-9) {
      throw common::InputError("mpm fill_box: box extent along axis " + std::to_string(d) +
                               " must be a positive whole number of cells");
    }
  }
  const common::Vec3 step = grid.spacing.cwiseQuotient(points_per_cell.cast<double>());
  const double vol = step.prod();
  std::int64_t next =
      points.id.empty() ? 0 : *std::max_element(points.id.begin(), points.id.end()) + 1;
  std::size_t added = 0;
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        const common::Vec3 pos = lo + step.cwiseProduct(common::Vec3(i + 0.5, j + 0.5, k + 0.5));
        points.add(next++, pos, density * vol, vol, 0.5 * step, material_id);
        ++added;
      }
    }
  }
  return added;
}

std::size_t fill_box(MaterialPoints& points, const Grid& grid, const common::Vec3& lo,
                     const common::Vec3& hi, int points_per_cell, double density,
                     std::int32_t material_id) {
  return fill_box(points, grid, lo, hi, common::Vec3i::Constant(points_per_cell), density,
                  material_id);
}

}  // namespace mpm
