// Named-field state interfaces: how state crosses module borders (docs/architecture.md).
// A module writes its state as named flat arrays ("contacts/shear_force"); the farm maps them to
// HDF5 datasets or MPI buffers without knowing what they mean. Shapes are flat: a field of N
// vectors is written as 3N doubles and the reader knows its layout.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace common {

/// Receives named fields. Names are '/'-separated paths; each name is written at most once.
class StateWriter {
 public:
  virtual ~StateWriter() = default;
  virtual void write(std::string_view name, std::span<const double> data) = 0;
  virtual void write(std::string_view name, std::span<const std::int64_t> data) = 0;
};

/// Gives back named fields written by a StateWriter. A missing field is an InputError that names it
/// (a checkpoint is user input).
class StateReader {
 public:
  virtual ~StateReader() = default;
  [[nodiscard]] virtual std::vector<double> read_f64(std::string_view name) const = 0;
  [[nodiscard]] virtual std::vector<std::int64_t> read_i64(std::string_view name) const = 0;
  [[nodiscard]] virtual bool has(std::string_view name) const = 0;
};

}  // namespace common
