// Plain packing text format (reference README section 8): '#' comments, "CELL Lx Ly Lz",
// "HSIZE" + 9 numbers (cell matrix row-major, columns are the cell vectors), "x y z r" per sphere.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "dem/periodic_cell.hpp"

namespace dem {

/// Geometry of a packing: cell and spheres (no velocities, no contact history).
struct Packing {
  PeriodicCell cell;            ///< cell matrix [m] (l is zero)
  std::vector<common::Vec3> x;  ///< centres [m]
  std::vector<double> r;        ///< radii [m]
};

/// Read a packing file. Throws common::InputError naming file:line and the rule broken.
[[nodiscard]] Packing read_packing(const std::string& path);
/// Write a packing file (17 significant digits: the round trip is exact).
void write_packing(const std::string& path, const Packing& packing,
                   const std::string& comment = "");
/// Tile a packing n x n x n times (exact periodic copies).
[[nodiscard]] Packing tile_packing(const Packing& packing, int n);
/// Tile a packing n[0] x n[1] x n[2] times along its cell vectors (exact periodic copies: the
/// same state in a larger cell). Throws common::InputError for a count < 1.
[[nodiscard]] Packing tile_packing(const Packing& packing, const std::array<int, 3>& n);

}  // namespace dem
