// Structured background grid: geometry helpers and nodal field storage.
#include "mpm/grid.hpp"

#include <string>

#include "common/errors.hpp"
#include "mpm/parallel.hpp"

namespace mpm {

common::Vec3i Grid::node_ijk(std::int64_t index) const {
  const common::Vec3i n = nodes();
  const auto i = static_cast<int>(index % n[0]);
  const std::int64_t rest = index / n[0];
  const auto j = static_cast<int>(rest % n[1]);
  const auto k = static_cast<int>(rest / n[1]);
  return {i, j, k};
}

common::Vec3 Grid::node_position(std::int64_t index) const {
  const common::Vec3i ijk = node_ijk(index);
  return origin + spacing.cwiseProduct(ijk.cast<double>());
}

void Grid::validate() const {
  for (int d = 0; d < 3; ++d) {
    if (!(spacing[d] > 0.0)) {
      throw common::InputError("mpm grid: spacing[" + std::to_string(d) +
                               "] = " + std::to_string(spacing[d]) + ": must be > 0 m");
    }
    if (cells[d] < 1) {
      throw common::InputError("mpm grid: cells[" + std::to_string(d) +
                               "] = " + std::to_string(cells[d]) + ": must be >= 1");
    }
  }
}

void GridFields::resize(const Grid& grid) {
  const auto n = static_cast<std::size_t>(grid.num_nodes());
  mass.assign(n, 0.0);
  momentum.assign(n, common::Vec3::Zero());
  force.assign(n, common::Vec3::Zero());
  velocity.assign(n, common::Vec3::Zero());
  acceleration.assign(n, common::Vec3::Zero());
  is_active.assign(n, 0);
  fixed.assign(n, 0);
  wall_dv.assign(n, common::Vec3::Zero());
  active.clear();
}

void GridFields::clear_active() {
  for_each_index(static_cast<std::int64_t>(active.size()), [&](std::int64_t k) {
    const auto u = static_cast<std::size_t>(active[static_cast<std::size_t>(k)]);
    mass[u] = 0.0;
    momentum[u].setZero();
    force[u].setZero();
    velocity[u].setZero();
    acceleration[u].setZero();
    is_active[u] = 0;
    fixed[u] = 0;
    wall_dv[u].setZero();
  });
  active.clear();
}

}  // namespace mpm
