// Time series output of a run: one row per output step, written progressively to CSV (so a
// killed run keeps what it had) and, on finish(), to an HDF5 file with one dataset per column.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace app {

struct Column {
  std::string name;  ///< CSV header and HDF5 dataset name
  std::string unit;  ///< written as the dataset's "unit" attribute ("" for none)
};

class SeriesWriter {
 public:
  /// Creates `<dir>/<stem>.csv` at once (header line); the HDF5 file is written by finish().
  SeriesWriter(const std::filesystem::path& dir, const std::string& stem,
               std::vector<Column> columns);
  /// Appends one row (one value per column) and flushes it to the CSV file.
  void add(const std::vector<double>& row);
  /// Writes `<dir>/<stem>.h5` atomically (common::publish_file). Throws common::IoError.
  void finish(const std::string& title);
  [[nodiscard]] std::size_t rows() const { return data_.empty() ? 0 : data_[0].size(); }

 private:
  std::filesystem::path dir_;
  std::string stem_;
  std::vector<Column> columns_;
  std::vector<std::vector<double>> data_;  ///< per column
  std::ofstream csv_;
};

}  // namespace app
