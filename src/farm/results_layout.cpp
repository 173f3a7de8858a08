// results.h5's layout: series table, attributes, HDF5 helpers (see results_layout.hpp).
#include "farm/results_layout.hpp"

#include <algorithm>
#include <iterator>
#include <string_view>

#include "farm/micro_model.hpp"
#include "farm/results.hpp"

namespace farm::results_detail {

namespace {
using h5::check;
using h5::Handle;
}  // namespace

using h5::check;
using h5::Handle;

// Sign conventions: stress tensors are Cauchy, tension positive; p, q and the strains of
// /means are compression positive (root attribute "conventions", docs/reference/outputs.md).
constexpr SeriesSpec kSeriesTable[] = {
    {"time", false, 0, '-', "s", "MPM time of the row"},
    {"step", true, 0, '-', "", "MPM step of the row"},
    {"rve/stress", false, 9, 'r', "Pa",
     "Cauchy stress of every RVE (order of /rve/id), row-major 3x3 [row, rve, 9], TENSION "
     "positive"},
    {"points/x", false, 3, 'p', "m",
     "position of every material point (order of /points/id) [row, point, xyz]"},
    {"points/stress", false, 9, 'p', "Pa",
     "Cauchy stress of every point, row-major 3x3 [row, point, 9], TENSION positive"},
    {"points/volume", false, 1, 'p', "m^3", "current volume of every point (J V0)"},
    {"means/eps_ax", false, 0, '-', "-",
     "axial strain 1 - mean_p F_aa (a = output.axial_axis of the job), compression positive; "
     "NOT logarithmic: -ln(1 - eps_ax) is the logarithmic strain"},
    {"means/eps_v", false, 0, '-', "-",
     "volumetric strain 1 - sum_p V_p / sum_p V0_p, compression positive; NOT logarithmic: "
     "-ln(1 - eps_v) is the logarithmic strain"},
    {"means/p", false, 0, '-', "Pa", "mean over RVEs of p, compression positive"},
    {"means/q", false, 0, '-', "Pa", "mean over RVEs of the von Mises q"},
    {"points/velocity", false, 3, 'p', "m/s", "velocity of every material point [row, point, xyz]"},
    {"points/displacement", false, 3, 'p', "m",
     "displacement x - x0 of every point from its position at t = 0 (the job's points) [row, "
     "point, xyz]"},
    {"points/F", false, 9, 'p', "-",
     "deformation gradient F = dx/dx0 of every point, row-major 3x3 [row, point, 9] (any strain "
     "follows from it: Green-Lagrange (F^T F - I)/2, logarithmic ln(V) of F = V R)"},
};

// The two id datasets (written once, not per row).
constexpr const char* kRveIdDescription =
    "RVE ids, ascending: the order of the RVE axis of every /rve series";
constexpr const char* kPointIdDescription =
    "material point ids in the solver's slot order: the order of the point axis of every /points "
    "series";

// Velocity constraints (mpm::Solver::reactions), written when the run has any; their names are
// the attribute "names" of /constraints, in order.
constexpr SeriesSpec kConstraintTable[] = {
    {"constraints/reaction", false, 3, 'c', "N",
     "force each velocity constraint exerts ON the material in the row's step, sum over its "
     "nodes of m (a after it - a before it) [row, constraint, xyz] (order: attribute names of "
     "/constraints)"},
    {"constraints/displacement", false, 3, 'c', "m",
     "displacement of each constraint: integral of its prescribed velocity over the time it was "
     "active [row, constraint, xyz]"},
};

/// UTF-8 variable-length string attribute `name` of `obj`, replacing one of that name (h5py
/// returns it as str, a fixed-length one as bytes).
void put_attr(hid_t obj, const char* name, const std::string& value) {
  if (H5Aexists(obj, name) > 0) check(H5Adelete(obj, name), std::string("delete ") + name);
  Handle type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
  Handle a(check(H5Acreate2(obj, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 std::string("create attribute ") + name),
           H5Aclose);
  const char* v = value.c_str();
  check(H5Awrite(a.get(), type.get(), &v), std::string("write attribute ") + name);
}

void put_attr(hid_t obj, const char* name, std::int64_t value) {
  if (H5Aexists(obj, name) > 0) check(H5Adelete(obj, name), std::string("delete ") + name);
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
  Handle a(check(H5Acreate2(obj, name, H5T_NATIVE_INT64, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 std::string("create attribute ") + name),
           H5Aclose);
  check(H5Awrite(a.get(), H5T_NATIVE_INT64, &value), std::string("write attribute ") + name);
}

/// File access of the writer: without HDF5's file lock, so that h5py, h5dump or ParaView can open
/// results.h5 while a run writes it (with the lock they fail with errno 11, EAGAIN). Two runs
/// never write one directory: the output directory's own lock (app/run/output_dir.hpp) refuses it.
Handle writer_access() {
  Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
#if H5_VERSION_GE(1, 10, 7)
  check(H5Pset_file_locking(fapl.get(), 0, 1), "H5Pset_file_locking");
#endif
  return fapl;
}

/// Attributes of results.h5: what the file is (root) and what every dataset holds.
void describe(hid_t file) {
  put_attr(file, "format", std::string(ResultsWriter::kFormat));
  put_attr(file, "format_version", ResultsWriter::kFormatVersion);
  put_attr(file, "software", std::string("mpmxdem"));
  put_attr(file, "software_version", std::string(MPMXDEM_SOFTWARE_VERSION));
  put_attr(file, "conventions",
           std::string("SI units (attribute unit of every dataset; '-' dimensionless, '' a "
                       "count). Stress tensors: Cauchy, TENSION positive, row-major 3x3. p, q "
                       "and the strains of /means: COMPRESSION positive. p = -tr(sigma)/3, "
                       "q = sqrt(3/2 s:s) (von Mises). First dimension: one row per output "
                       "step (/step, /time)."));
  auto dataset = [&](const char* name, const char* unit, const char* description) {
    Handle d(check(H5Dopen2(file, name, H5P_DEFAULT), std::string("open ") + name), H5Dclose);
    put_attr(d.get(), "unit", std::string(unit));
    put_attr(d.get(), "description", std::string(description));
  };
  dataset("rve/id", "", kRveIdDescription);
  dataset("points/id", "", kPointIdDescription);
  for (const SeriesSpec& s : series()) dataset(s.name, s.unit, s.description);
}

std::vector<hsize_t> row_dims(const SeriesSpec& s, std::size_t n_rve, std::size_t n_pts,
                              std::size_t n_con) {
  std::vector<hsize_t> d;
  if (s.over == 'r') d.push_back(n_rve);
  if (s.over == 'p') d.push_back(n_pts);
  if (s.over == 'c') d.push_back(n_con);
  if (s.per_item > 1) d.push_back(static_cast<hsize_t>(s.per_item));
  return d;
}

void write_static(hid_t file, const char* name, const std::vector<std::int64_t>& v) {
  Handle lcpl(check(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate"), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  const hsize_t dims[1] = {v.size()};
  Handle space(check(H5Screate_simple(1, dims, nullptr), "H5Screate_simple"), H5Sclose);
  Handle d(check(H5Dcreate2(file, name, H5T_NATIVE_INT64, space.get(), lcpl.get(), H5P_DEFAULT,
                            H5P_DEFAULT),
                 std::string("create ") + name),
           H5Dclose);
  if (!v.empty()) {
    check(H5Dwrite(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
          std::string("write ") + name);
  }
}

// The RVEs' per-step fields (farm::kReportFields) come after the first series, the points'
// copies of them after the second, the grain-scale measures (farm::kMeasureFields) after the third.
constexpr std::string_view kReportsAfter = "rve/stress";
constexpr std::string_view kPointReportsAfter = "points/volume";
constexpr std::string_view kMeasuresAfter = "means/q";

std::span<const SeriesSpec> series() {
  // The datasets' names, alive as long as the table that points at them.
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const ReportField& f : kReportFields) v.push_back(std::string("rve/") + f.name);
    for (const ReportField& f : kReportFields) v.push_back(std::string("points/") + f.name);
    for (const MeasureField& f : kMeasureFields) v.push_back(std::string("rve/") + f.name);
    return v;
  }();
  static const std::vector<SeriesSpec> all = [] {
    const std::size_t nr = std::size(kReportFields);
    std::vector<SeriesSpec> v;
    for (const SeriesSpec& s : kSeriesTable) {
      v.push_back(s);
      if (s.name == kReportsAfter) {
        for (std::size_t i = 0; i < nr; ++i) {
          const ReportField& f = kReportFields[i];
          v.push_back(
              {names[i].c_str(), f.type != ReportType::real, 1, 'r', f.unit, f.description});
        }
      } else if (s.name == kPointReportsAfter) {
        for (std::size_t i = 0; i < nr; ++i) {
          const ReportField& f = kReportFields[i];
          if (f.point_description == nullptr) continue;
          v.push_back({names[nr + i].c_str(), f.type != ReportType::real, 1, 'p', f.unit,
                       f.point_description});
        }
      } else if (s.name == kMeasuresAfter) {
        for (std::size_t i = 0; i < std::size(kMeasureFields); ++i) {
          const MeasureField& f = kMeasureFields[i];
          v.push_back({names[2 * nr + i].c_str(), false, f.components, 'r', f.unit, f.description});
        }
      }
    }
    return v;
  }();
  return all;
}
std::span<const SeriesSpec> constraint_series() { return kConstraintTable; }

bool added_later(const std::string& name) {
  static constexpr const char* kAdded[] = {"points/volume", "points/velocity",
                                           "points/displacement", "points/F"};
  // Every grain-scale measure came after the first files, and so does every one added now.
  return std::any_of(std::begin(kAdded), std::end(kAdded),
                     [&](const char* a) { return name == a; }) ||
         std::any_of(std::begin(kMeasureFields), std::end(kMeasureFields),
                     [&](const MeasureField& f) { return name == std::string("rve/") + f.name; });
}

}  // namespace farm::results_detail

namespace farm {

std::string results_reference_markdown() {
  using results_detail::constraint_series;
  using results_detail::series;
  std::string out =
      "# results.h5: every dataset\n\n"
      "Generated from the tables the writer creates results.h5 with (src/farm/results_layout.cpp, "
      "the grain-scale measures from farm::kMeasureFields): `mpmxdem schema --outputs > "
      "docs/reference/results_h5.md`. How to read them: [outputs.md](outputs.md). Every dataset "
      "holds these two as the attributes `unit` (SI; `-` dimensionless, empty for counts and "
      "bits) and `description`. nt: rows (output steps), n: RVEs, m: material points, nc: "
      "velocity constraints (the group `/constraints` exists when the job has any).\n\n"
      "| dataset | shape | type | unit | description |\n|---|---|---|---|---|\n";
  auto row = [&out](const std::string& name, const std::string& shape, const char* type,
                    const char* unit, const char* description) {
    std::string d = description;
    for (std::size_t i = 0; (i = d.find('|', i)) != std::string::npos; i += 2)
      d.replace(i, 1, "\\|");
    out += "| `/" + name + "` | " + shape + " | " + type + " | " + unit + " | " + d + " |\n";
  };
  row("rve/id", "[n]", "int64", "", results_detail::kRveIdDescription);
  row("points/id", "[m]", "int64", "", results_detail::kPointIdDescription);
  auto shape = [](const SeriesSpec& s) {
    std::string d = "[nt";
    if (s.over == 'r') d += ", n";
    if (s.over == 'p') d += ", m";
    if (s.over == 'c') d += ", nc";
    if (s.per_item > 1) d += ", " + std::to_string(s.per_item);  // as row_dims
    return d + "]";
  };
  for (const SeriesSpec& s : series()) {
    row(s.name, shape(s), s.integer ? "int64" : "float64", s.unit, s.description);
  }
  for (const SeriesSpec& s : constraint_series()) {
    row(s.name, shape(s), s.integer ? "int64" : "float64", s.unit, s.description);
  }
  return out;
}

}  // namespace farm
