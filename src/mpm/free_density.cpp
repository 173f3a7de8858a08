// The density of stress-free points (see header).
#include "mpm/free_density.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace mpm {

FreeDensity free_density_from_string(std::string_view name) {
  if (const auto f = common::value_of(kFreeDensityNames, name)) return *f;
  throw common::InputError("mpm.free_density must be one of " +
                           common::names_list(kFreeDensityNames) + ", not \"" + std::string(name) +
                           "\"");
}

std::string_view to_string(FreeDensity f) { return common::name_of(kFreeDensityNames, f); }

void grid_density(const Grid& grid, const StencilCache& cache, const MaterialPoints& points,
                  std::vector<double>& node_m, std::vector<double>& node_v,
                  std::vector<double>& rho) {
  const std::size_t n = points.size();
  const auto nodes = static_cast<std::size_t>(grid.num_nodes());
  node_m.assign(nodes, 0.0);
  node_v.assign(nodes, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const double m = points.mass[p];
    const double v = points.volume[p];
    for_each_node(grid, cache, p, [&](std::int64_t node, double S, const common::Vec3&) {
      const auto i = static_cast<std::size_t>(node);
      node_m[i] += S * m;
      node_v[i] += S * v;
    });
  }
  rho.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    double num = 0.0;
    double den = 0.0;
    for_each_node(grid, cache, p, [&](std::int64_t node, double S, const common::Vec3&) {
      const auto i = static_cast<std::size_t>(node);
      if (!(node_v[i] > 0.0)) return;
      num += S * node_m[i] * (node_m[i] / node_v[i]);
      den += S * node_m[i];
    });
    rho[p] = den > 0.0 ? num / den : points.mass[p] / points.volume[p];
  }
}

std::size_t limit_free_dilation(const std::vector<double>& rho, int plane_strain_axis, double dt,
                                MaterialPoints& points) {
  std::size_t changed = 0;
  int active = 0;
  for (int a = 0; a < 3; ++a) active += a == plane_strain_axis ? 0 : 1;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!points.stress[p].isZero(0.0)) continue;
    common::Mat3& L = points.L[p];
    const double own = L.trace();
    if (!(own > 0.0)) continue;  // a compression (or nothing) of its own: kept
    // The largest dilation rate that keeps it at most as loose as the material around it.
    const double room = std::max(std::log(points.mass[p] / (rho[p] * points.volume[p])), 0.0) / dt;
    if (own <= room) continue;
    const double shift = (room - own) / static_cast<double>(active);
    for (int a = 0; a < 3; ++a) {
      if (a != plane_strain_axis) L(a, a) += shift;
    }
    ++changed;
  }
  return changed;
}

}  // namespace mpm
