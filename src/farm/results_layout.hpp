// results.h5's layout (internal to src/farm/results*.cpp): the table of its series with their
// units and descriptions, the attributes, and small HDF5 helpers of the writer. docs/design/farm.md,
// "Outputs".
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "farm/h5_util.hpp"

namespace farm {

struct SeriesSpec {  // declared in results.hpp
  const char* name;
  bool integer;
  int per_item;             ///< values per RVE or point (0: scalar per row)
  char over;                ///< 'r' RVEs, 'p' points, 'c' constraints, '-' none
  const char* unit;         ///< attribute "unit" ("-": dimensionless, "": a count or bits)
  const char* description;  ///< attribute "description"
};

namespace results_detail {

/// Every series of every results.h5, in the order they are created.
std::span<const SeriesSpec> series();
/// Velocity constraints' series (written when the run has constraints).
std::span<const SeriesSpec> constraint_series();
/// Series added after format 1's first files: a file being continued that lacks one gets it
/// with NaN rows up to the restart (points/volume: issue 15; the point fields and grain-scale
/// measures: issue 19).
bool added_later(const std::string& name);

/// UTF-8 variable-length string attribute `name` of `obj`, replacing one of that name.
void put_attr(hid_t obj, const char* name, const std::string& value);
void put_attr(hid_t obj, const char* name, std::int64_t value);
/// File access of the writer: without HDF5's file lock (a run can be read while it writes).
h5::Handle writer_access();
/// Attributes of results.h5: what the file is (root) and what every dataset holds.
void describe(hid_t file);
/// Dimensions of one row of `s` (after the row axis).
std::vector<hsize_t> row_dims(const SeriesSpec& s, std::size_t n_rve, std::size_t n_pts,
                              std::size_t n_con);
/// A fixed-size int64 dataset (ids).
void write_static(hid_t file, const char* name, const std::vector<std::int64_t>& v);
/// The first `rows` values of a 1-D dataset.
template <class T>
std::vector<T> read_rows(hid_t file, const std::string& name, hsize_t rows) {
  std::vector<T> v(rows);
  if (rows == 0) return v;
  h5::Handle d(h5::check(H5Dopen2(file, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  h5::Handle fs(H5Dget_space(d.get()), H5Sclose);
  const hsize_t start[1] = {0};
  const hsize_t count[1] = {rows};
  H5Sselect_hyperslab(fs.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  h5::Handle ms(H5Screate_simple(1, count, nullptr), H5Sclose);
  h5::check(H5Dread(d.get(), h5::native_type<T>(), ms.get(), fs.get(), H5P_DEFAULT, v.data()),
            "read " + name);
  return v;
}

}  // namespace results_detail
}  // namespace farm
