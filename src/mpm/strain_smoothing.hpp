// Strain smoothing: every material point of a grid cell gets the cell's volume-averaged velocity
// gradient before the material update (the cell-based averaging of Anura3D's mixed integration;
// docs/design/mpm.md, "Strain smoothing"). A cure for the checkerboard of softening single-cell
// tests.
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "common/choice_table.hpp"
#include "common/types.hpp"
#include "mpm/grid.hpp"

namespace mpm {

/// Which velocity gradient the material update sees.
enum class StrainSmoothing {
  none,  ///< each point its own L (the default)
  cell,  ///< each point the volume-weighted mean L of the points in its grid cell, and the
         ///< internal forces from the cell's mean stress (no hourglass forces; docs/design/mpm.md)
};
/// The job's names (mpm.strain_smoothing).
inline constexpr std::array<common::Named<StrainSmoothing>, 2> kStrainSmoothingNames{
    {{"none", StrainSmoothing::none}, {"cell", StrainSmoothing::cell}}};

/// "none" or "cell"; throws common::InputError otherwise.
[[nodiscard]] StrainSmoothing strain_smoothing_from_string(std::string_view name);
[[nodiscard]] std::string_view to_string(StrainSmoothing s);

/// Linear index (i fastest) of the grid cell holding x; a point on a cell face belongs to the
/// cell above it, one on the grid's upper face to the last cell (indices clamped to the grid).
[[nodiscard]] std::int64_t cell_of(const Grid& grid, const common::Vec3& x);

/// Replaces each L[p] by sum_q V_q L_q / sum_q V_q over the points q in the cell of x[p]
/// (volume [m^3]; L: any tensor per point, the velocity gradient [1/s] or the stress [Pa]). Pre: x,
/// volume and L have the same size, volumes > 0. The sums run in point order within each cell: the
/// result depends on neither thread count nor cell count. `scratch` is reused between calls (no
/// allocation in the steady state).
void average_per_cell(const Grid& grid, const std::vector<common::Vec3>& x,
                      const std::vector<double>& volume, std::vector<common::Mat3>& L,
                      std::vector<std::pair<std::int64_t, std::int64_t>>& scratch);

}  // namespace mpm
