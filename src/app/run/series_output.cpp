// CSV + HDF5 time series: see series_output.hpp.
#include "app/run/series_output.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"

namespace app {

SeriesWriter::SeriesWriter(const std::filesystem::path& dir, const std::string& stem,
                           std::vector<Column> columns)
    : dir_(dir), stem_(stem), columns_(std::move(columns)), data_(columns_.size()) {
  const auto path = dir_ / (stem_ + ".csv");
  csv_.open(path, std::ios::trunc);
  if (!csv_) throw common::InputError(fmt::format("cannot write '{}'", path.string()));
  for (std::size_t c = 0; c < columns_.size(); ++c) csv_ << (c ? "," : "") << columns_[c].name;
  csv_ << "\n";
  csv_.flush();
}

void SeriesWriter::add(const std::vector<double>& row) {
  MPMXDEM_CHECK(row.size() == columns_.size(), "series row has the wrong number of columns");
  for (std::size_t c = 0; c < row.size(); ++c) {
    data_[c].push_back(row[c]);
    csv_ << (c ? "," : "") << fmt::format("{:.10g}", row[c]);
  }
  csv_ << "\n";
  csv_.flush();
}

void SeriesWriter::finish(const std::string& title) {
  const auto path = dir_ / (stem_ + ".h5");
  const auto tmp = common::staging_path(path);
  const hid_t file = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw common::IoError(fmt::format("cannot create '{}'", tmp.string()));
  auto put_string_attr = [](hid_t obj, const char* name, const std::string& value) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, value.empty() ? 1 : value.size());
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attr, type, value.empty() ? "" : value.c_str());
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
  };
  put_string_attr(file, "title", title);
  bool ok = true;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const hsize_t n = data_[c].size();
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t ds = H5Dcreate2(file, columns_[c].name.c_str(), H5T_NATIVE_DOUBLE, space,
                                H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = ok && ds >= 0 &&
         H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data_[c].data()) >= 0;
    if (ds >= 0) {
      put_string_attr(ds, "unit", columns_[c].unit);
      H5Dclose(ds);
    }
    H5Sclose(space);
  }
  ok = H5Fclose(file) >= 0 && ok;
  if (!ok) throw common::IoError(fmt::format("writing '{}' failed", tmp.string()));
  common::publish_file(tmp, path);
}

}  // namespace app
