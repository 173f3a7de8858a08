// The dilation of a stress-free point: its own (from its velocity gradient), or no further than
// the density of the material around it (read from the grid). docs/design/mpm.md, "Density of
// stress-free points".
#pragma once

#include <string_view>
#include <vector>

#include "common/choice_table.hpp"
#include "mpm/grid.hpp"
#include "mpm/material_points.hpp"
#include "mpm/transfers.hpp"

namespace mpm {

/// Which volume change a stress-free point (a disconnected material) takes in a step.
enum class FreeDensity {
  point,  ///< its own L: det(I + L dt), as every other point (the default)
  /// its own L, but no dilation beyond its neighbourhood's density m_p / rho_grid(x_p)
  grid,
};
/// The job's names (mpm.free_density).
inline constexpr std::array<common::Named<FreeDensity>, 2> kFreeDensityNames{
    {{"point", FreeDensity::point}, {"grid", FreeDensity::grid}}};

/// "point" or "grid"; throws common::InputError otherwise.
[[nodiscard]] FreeDensity free_density_from_string(std::string_view name);
[[nodiscard]] std::string_view to_string(FreeDensity f);

/// rho_grid at every point: rho_i = sum_q S_iq m_q / sum_q S_iq V_q at each node (a ratio, so
/// nodes at the material's edge, which collect from few points, are not diluted), then
/// sum_i S_ip m_i rho_i / sum_i S_ip m_i at the point [kg/m^3]. Sums in slot order (serial):
/// independent of threads. `node_m`, `node_v` are scratch (resized to the grid's nodes).
void grid_density(const Grid& grid, const StencilCache& cache, const MaterialPoints& points,
                  std::vector<double>& node_m, std::vector<double>& node_v,
                  std::vector<double>& rho);

/// FreeDensity::grid: for every point whose stress is exactly zero (it carried nothing after
/// its last update) and whose L dilates it, cuts the volumetric part of L over the `active` axes
/// (those not held by plane strain) to at most ln(m_p / (rho[p] V_p)) / dt (0 when it is already
/// looser than rho[p]): a stress-free point does not dilate beyond the density of the material
/// around it. A compression of its own, the deviatoric part and the spin are kept. Returns the
/// number of points changed. Pre: dt > 0, rho from grid_density for the same points.
std::size_t limit_free_dilation(const std::vector<double>& rho, int plane_strain_axis, double dt,
                                MaterialPoints& points);

}  // namespace mpm
