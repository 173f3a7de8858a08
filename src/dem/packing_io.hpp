// Plain packing text format (docs/validation/yade_reference.md section 8): '#' comments, "CELL Lx Ly Lz",
// "HSIZE" + 9 numbers (cell matrix row-major, columns are the cell vectors), "x y z r" per sphere.
// The cell lines may be written as comments ("# CELL ...", "# HSIZE ..."), as write_packing does,
// so that YADE's ymport.text reads our packings as they are.
#pragma once

#include <array>
#include <optional>
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

/// Read a packing file and check it (check_packing). Throws common::InputError naming file:line
/// and the rule broken.
[[nodiscard]] Packing read_packing(const std::string& path);
/// The same, with the cell sizes [m] given by the caller (job key dem.sample.cell) for a file
/// without a CELL or HSIZE line (YADE's yade.export.text carries none): used when the file has no
/// cell line; a cell line that disagrees with them (relative 1e-9) is refused, naming both.
[[nodiscard]] Packing read_packing(const std::string& path,
                                   const std::optional<common::Vec3>& cell);
/// Checks that a packing can be simulated, and names the first problem as "source:line: rule"
/// (line = lines[i] of sphere i; without lines, "source: sphere i"): at least 2 spheres; finite
/// positions, finite radii > 0; every diameter below the cell's smallest perpendicular width (a
/// larger sphere touches its own periodic image); no centre more than one cell length outside the
/// cell (fractional coordinate outside [-1, 2]: a unit mismatch, not something to wrap); no two
/// centres closer than half the sum of their radii (degenerate: spheres at one point); a solid
/// volume fraction in [0.01, 1] (radii and cell in different units). Throws common::InputError.
void check_packing(const Packing& packing, const std::string& source,
                   const std::vector<long>& lines = {});
/// Write a packing file (17 significant digits: the round trip is exact).
void write_packing(const std::string& path, const Packing& packing,
                   const std::string& comment = "");
/// Tile a packing n x n x n times (exact periodic copies).
[[nodiscard]] Packing tile_packing(const Packing& packing, int n);
/// Tile a packing n[0] x n[1] x n[2] times along its cell vectors (exact periodic copies: the
/// same state in a larger cell). Throws common::InputError for a count < 1.
[[nodiscard]] Packing tile_packing(const Packing& packing, const std::array<int, 3>& n);

}  // namespace dem
