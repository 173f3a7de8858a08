// Strain smoothing: every material point of a grid cell gets the cell's volume-averaged velocity
// gradient before the material update (the cell-based averaging of Anura3D's mixed integration;
// docs/design/mpm.md, "Strain smoothing"). A cure for the checkerboard of softening single-cell
// tests. Or only its volumetric part (B-bar cell by cell): the points of a cell dilate together.
#pragma once

#include <algorithm>
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
  volumetric,  ///< each point its own L with the trace of the cell's mean (B-bar), and the
               ///< internal forces from stresses with the cell's mean normal stress
};
/// The job's names (mpm.strain_smoothing).
inline constexpr std::array<common::Named<StrainSmoothing>, 3> kStrainSmoothingNames{
    {{"none", StrainSmoothing::none},
     {"cell", StrainSmoothing::cell},
     {"volumetric", StrainSmoothing::volumetric}}};

/// "none", "cell" or "volumetric"; throws common::InputError otherwise.
[[nodiscard]] StrainSmoothing strain_smoothing_from_string(std::string_view name);
[[nodiscard]] std::string_view to_string(StrainSmoothing s);

/// Linear index (i fastest) of the grid cell holding x; a point on a cell face belongs to the
/// cell above it, one on the grid's upper face to the last cell (indices clamped to the grid).
[[nodiscard]] std::int64_t cell_of(const Grid& grid, const common::Vec3& x);

/// Calls f(begin, end) for each run of `scratch` entries that share a grid cell: scratch is
/// filled with the (cell, point) pairs of x sorted by cell then point, so each cell's points come
/// in point order and the cells in index order (a result that depends on neither threads nor
/// ranks).
template <class F>
void for_each_cell(const Grid& grid, const std::vector<common::Vec3>& x,
                   std::vector<std::pair<std::int64_t, std::int64_t>>& scratch, F&& f) {
  const std::size_t n = x.size();
  scratch.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    scratch[p] = {cell_of(grid, x[p]), static_cast<std::int64_t>(p)};
  }
  std::sort(scratch.begin(), scratch.end());
  for (std::size_t begin = 0; begin < n;) {
    std::size_t end = begin;
    while (end < n && scratch[end].first == scratch[begin].first) ++end;
    f(begin, end);
    begin = end;
  }
}

/// Replaces each L[p] by sum_q V_q L_q / sum_q V_q over the points q in the cell of x[p]
/// (volume [m^3]; L: any tensor per point, the velocity gradient [1/s] or the stress [Pa]). Pre: x,
/// volume and L have the same size, volumes > 0. The sums run in point order within each cell: the
/// result depends on neither thread count nor cell count. `scratch` is reused between calls (no
/// allocation in the steady state).
void average_per_cell(const Grid& grid, const std::vector<common::Vec3>& x,
                      const std::vector<double>& volume, std::vector<common::Mat3>& L,
                      std::vector<std::pair<std::int64_t, std::int64_t>>& scratch);

/// Replaces the trace of each T[p] over the in-plane axes (every axis but thickness_axis; all
/// three when it is -1) by the volume-weighted mean of those traces over the points in the cell
/// of x[p], spreading the change equally over those axes' diagonal entries; the rest of T[p] is
/// its own. On the velocity gradient this is B-bar cell by cell (every point of a cell gets the
/// cell's volumetric rate, its own deviatoric rate and spin); on the stress, the cell's mean
/// normal stress. The operator is its own adjoint for sum_p V_p A_p : B_p, so the pair keeps the
/// forces' power equal to the material's. Same preconditions, order and scratch as
/// average_per_cell.
void average_trace_per_cell(const Grid& grid, const std::vector<common::Vec3>& x,
                            const std::vector<double>& volume, int thickness_axis,
                            std::vector<common::Mat3>& T,
                            std::vector<std::pair<std::int64_t, std::int64_t>>& scratch);

}  // namespace mpm
