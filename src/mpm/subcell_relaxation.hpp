// Sub-cell stress relaxation: the points of one grid cell exchange volume and shape so that
// their stresses approach the cell's mean, a pattern that the grid cannot see (the null space of
// the points-to-grid map) being relaxed where it would otherwise persist (docs/design/mpm.md,
// "Sub-cell stress relaxation").
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "mpm/grid.hpp"

namespace mpm {

/// Adds to each L[p] the strain rate -(sigma_p - sigma_bar) / (rho c^2 tau) over the in-plane
/// components (every row and column but thickness_axis's; all when it is -1), with sigma_bar
/// and rho the volume-weighted mean stress and the mass over the volume of the points in the
/// cell of x[p]: a point that carries more than its cell's mean extends, one that carries less
/// is compressed. `c` [m/s] is a wave speed of the material and `tau` [s] > 0 the relaxation
/// time. Over each cell sum_p V_p dL_p = 0 (the cell's deformation rate, which the grid sets,
/// is unchanged) and the stress power of the added rates, -sum_p V_p |sigma_p - sigma_bar|^2 /
/// (rho c^2 tau), is never positive. A cell of one point, or of equal stresses, is unchanged.
/// Sums in point order within each cell (for_each_cell): the result depends on neither threads
/// nor ranks. Pre: x, mass, volume, stress and L have one size, volumes and masses > 0.
void relax_subcell_stress(const Grid& grid, const std::vector<common::Vec3>& x,
                          const std::vector<double>& mass, const std::vector<double>& volume,
                          const std::vector<common::Mat3>& stress, int thickness_axis, double c,
                          double tau, std::vector<common::Mat3>& L,
                          std::vector<std::pair<std::int64_t, std::int64_t>>& scratch);

}  // namespace mpm
