// Structured background grid of hexahedral cells (geometry) and its nodal fields (SoA).
// Duverger et al. 2022 (MPMxDEM), section 2.1: nodes carry mass (eq. 7), forces (eqs. 5-6),
// velocities and accelerations (eq. 8).
#pragma once

#include <cstdint>
#include <vector>

#include "common/types.hpp"

namespace mpm {

/// Geometry of a uniform 3D grid: cells [origin + i*spacing, origin + (i+1)*spacing].
struct Grid {
  common::Vec3 origin = common::Vec3::Zero();   ///< lower corner [m]
  common::Vec3 spacing = common::Vec3::Ones();  ///< cell size per axis [m], > 0
  common::Vec3i cells = common::Vec3i::Ones();  ///< number of cells per axis, >= 1

  /// Nodes per axis (cells + 1).
  [[nodiscard]] common::Vec3i nodes() const { return cells.array() + 1; }
  [[nodiscard]] std::int64_t num_nodes() const {
    const common::Vec3i n = nodes();
    return std::int64_t{n[0]} * n[1] * n[2];
  }
  /// Linear node index of node (i, j, k): i fastest.
  [[nodiscard]] std::int64_t node_index(int i, int j, int k) const {
    const common::Vec3i n = nodes();
    return i + std::int64_t{n[0]} * (j + std::int64_t{n[1]} * k);
  }
  /// (i, j, k) of a linear node index.
  [[nodiscard]] common::Vec3i node_ijk(std::int64_t index) const;
  /// Position of a node [m].
  [[nodiscard]] common::Vec3 node_position(std::int64_t index) const;
  /// Upper corner [m].
  [[nodiscard]] common::Vec3 upper() const {
    return origin + spacing.cwiseProduct(cells.cast<double>());
  }
  /// Throws common::InputError when spacing or cells are not positive.
  void validate() const;
};

/// Nodal fields, one dense array per quantity over all nodes; only the nodes listed in `active`
/// (sorted, those inside the stencil of at least one point) are written or read in a step.
struct GridFields {
  std::vector<double> mass;                ///< m_v, eq. 7 [kg]
  std::vector<common::Vec3> momentum;      ///< sum_p m_p S_v v_p [kg m/s]
  std::vector<common::Vec3> force;         ///< f_v = f_int + f_ext, eqs. 5-6 [N]
  std::vector<common::Vec3> velocity;      ///< V_v at the start of the step [m/s]
  std::vector<common::Vec3> acceleration;  ///< a_v, eq. 8 [m/s^2]
  std::vector<std::int64_t> active;        ///< sorted node indices touched this step
  std::vector<char> is_active;             ///< 1 for nodes in `active`
  /// Bit d set: component d of the node's velocity is prescribed this step (set by
  /// apply_velocity_constraints; the damping of eq. 8 then ignores that component).
  std::vector<std::uint8_t> fixed;
  /// The walls' momentum-stage correction of V_v at the start of the step, V_corrected -
  /// V_projected [m/s] (apply_velocity_constraints; zero at other nodes): with
  /// SolverConfig::wall_impulse_on_points the FLIP increments of the points see it.
  std::vector<common::Vec3> wall_dv;

  /// Sizes every array for `grid`, all zero.
  void resize(const Grid& grid);
  /// Zeroes the fields of the active nodes and empties the active list.
  void clear_active();
};

}  // namespace mpm
