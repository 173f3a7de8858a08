// Grain-scale views of one periodic cell as VTK XML files that ParaView's default readers open:
// the spheres (points), the contact network (lines between the centres, drawn along the branch
// vector so that a contact across the periodic boundary has its true length) and the cell
// (a hexahedron), grouped by a multiblock file. Format and arrays: docs/design/dem.md "Grain-scale views".
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "dem/simulation.hpp"

namespace dem {

/// One file of a view: its name inside the output directory and its whole content.
struct VtkFile {
  std::string name;
  std::string text;
};

/// The view of `sim` as four files (ASCII VTK XML, every value with 17 significant digits):
///   <stem>_spheres.vtp   one point (and vertex cell) per sphere, at its centre wrapped into the
///                        cell (fractional coordinates in [0, 1)); point data id, radius,
///                        velocity (u + L x at the drawn position), fluctuating_velocity (u),
///                        spin, force, torque, contacts (active contacts of the sphere)
///   <stem>_contacts.vtp  one line per active contact from the wrapped centre of sphere 1 to that
///                        point plus the branch x2 + H k - x1; cell data sphere1, sphere2,
///                        normal_force (magnitude), normal_force_vector, shear_force (vector),
///                        shear_force_magnitude, force (on sphere 2), normal, rolling_moment,
///                        twisting_moment, overlap
///   <stem>_cell.vtu      the cell H [0,1]^3 as one hexahedron; cell data stress (Love-Weber,
///                        tension positive), p, q, void_ratio, z, z_mech, fabric, unbalanced,
///                        kinetic_energy, volume (dem::measure of the current state)
///   <stem>.vtm           the three as named blocks spheres, contacts, cell
/// Forces and moments are those of the last force computation. @pre stem is a plain file name.
[[nodiscard]] std::vector<VtkFile> vtk_view(const Simulation& sim, const std::string& stem);

/// One entry of a time series: the time and the file (a view's .vtm) shown at that time.
struct VtkSeriesEntry {
  double time = 0.0;  ///< [s]
  std::string file;   ///< relative to the series file
};

/// A ParaView data collection (.pvd) of `entries`: ParaView opens it as one dataset with a time
/// per entry. Entries are written in the order given.
[[nodiscard]] std::string vtk_series(const std::vector<VtkSeriesEntry>& entries);
/// The entries of a collection written by vtk_series. Throws common::InputError naming `what`
/// (the file) when the text is not such a collection.
[[nodiscard]] std::vector<VtkSeriesEntry> read_vtk_series(const std::string& text,
                                                          const std::string& what);
/// The entries of the series file `path`; none when it does not exist. Throws
/// common::InputError naming the file when it cannot be read or is not such a collection.
[[nodiscard]] std::vector<VtkSeriesEntry> read_vtk_series_file(const std::filesystem::path& path);

/// The names every grain view of an RVE uses (`inspect --vtk` and the run's [output.grains]): the
/// stem of the view of RVE `id` at MPM step `step`, "rve_<id>_step_<step>" (its multiblock file is
/// stem + ".vtm"), and the RVE's time series, "rve_<id>.pvd".
[[nodiscard]] std::string rve_view_stem(std::int64_t id, std::int64_t step);
[[nodiscard]] std::string rve_series_name(std::int64_t id);

/// `entries` with `add` put in: an entry of the same file is replaced; sorted by time, then file.
[[nodiscard]] std::vector<VtkSeriesEntry> merge_vtk_series(std::vector<VtkSeriesEntry> entries,
                                                           const VtkSeriesEntry& add);

/// Writes `files` into the existing directory `dir`, all or nothing: every file is staged
/// (common::staging_path) first; if one cannot be staged, the staged ones are removed and
/// nothing is published; then each is published (common::publish_file).
/// Throws common::IoError naming the file and the system's reason.
void write_vtk_files(const std::filesystem::path& dir, const std::vector<VtkFile>& files);

}  // namespace dem
