// Material points as a structure of arrays (one vector per property), Cabana/ExaMPM style.
// Duverger et al. 2022, section 2.1: each point carries m_p, V_p, sigma_p, and moves (eqs. 9-10).
#pragma once

#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "mpm/grid.hpp"

namespace mpm {

/// All material points of a run. Every vector has size() entries; index p is the point's slot,
/// id[p] its stable id (what the material model sees).
struct MaterialPoints {
  std::vector<std::int64_t> id;           ///< stable point id (unique)
  std::vector<common::Vec3> x;            ///< position [m]
  std::vector<common::Vec3> v;            ///< velocity [m/s]
  std::vector<double> mass;               ///< m_p [kg]
  std::vector<double> volume;             ///< current volume V_p [m^3]
  std::vector<double> volume0;            ///< initial volume [m^3]
  std::vector<common::Vec3> half_width0;  ///< initial half-widths of the point's domain [m]
  std::vector<common::Mat3> stress;       ///< Cauchy stress, tension positive [Pa]
  std::vector<common::Mat3> F;            ///< deformation gradient [-]
  std::vector<common::Mat3> L;            ///< velocity gradient dv/dx of the last step [1/s]
  /// Affine velocity of the APIC transfer (Jiang et al. 2015), the grid's end-of-step velocity
  /// gradient at the point; zero (and unused) with the FLIP/PIC transfer [1/s].
  std::vector<common::Mat3> C;
  std::vector<std::int32_t> material;  ///< index into the solver's material list

  [[nodiscard]] std::size_t size() const { return x.size(); }
  /// Appends one point at rest with F = I, zero stress and L.
  void add(std::int64_t point_id, const common::Vec3& position, double point_mass,
           double point_volume, const common::Vec3& half_width, std::int32_t material_id);
  /// Resizes every array to n (new entries: identity F, zeros elsewhere).
  void resize(std::size_t n);
  /// Throws common::InputError when the arrays disagree in size, ids repeat, or a mass,
  /// volume or half-width is not positive.
  void validate() const;
};

/// Fills the box [lo, hi] (aligned with the grid's cells) with points_per_cell[d] points per cell
/// along each axis d, at the regular positions (k + 1/2)/points_per_cell[d] of each cell (for 2
/// per cell: the 1/4 and 3/4 positions of the paper's single-cell test; [2, 1, 2]: one point
/// through the thickness of a plane-strain grid, docs/design/mpm.md "Plane strain"). Each point's domain
/// has half-widths spacing[d] / (2 points_per_cell[d]). Mass = density * volume, ids continue
/// from the largest existing id + 1. Returns the number of points added. Throws
/// common::InputError when a count is < 1, the density is not positive, or the box is not a whole
/// number of cells.
std::size_t fill_box(MaterialPoints& points, const Grid& grid, const common::Vec3& lo,
                     const common::Vec3& hi, const common::Vec3i& points_per_cell, double density,
                     std::int32_t material_id);
/// The same with points_per_cell points along every axis.
std::size_t fill_box(MaterialPoints& points, const Grid& grid, const common::Vec3& lo,
                     const common::Vec3& hi, int points_per_cell, double density,
                     std::int32_t material_id);

}  // namespace mpm
