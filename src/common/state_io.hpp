// Named-field state interfaces: how state crosses module borders (docs/design/architecture.md).
// A module writes its state as named flat arrays ("contacts/shear_force"); the farm maps them to
// HDF5 datasets or MPI buffers without knowing what they mean. Shapes are flat: a field of N
// vectors is written as 3N doubles and the reader knows its layout. A parameter is a field of its
// own ("params/material/young", one value), never a position in an array: adding one adds a field
// instead of silently shifting a layout (docs/reference/checkpoint.md).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.hpp"

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

/// A named scalar: a field of one value.
inline void write_scalar(StateWriter& w, std::string_view name, double value) {
  w.write(name, std::span<const double>(&value, 1));
}
inline void write_scalar(StateWriter& w, std::string_view name, std::int64_t value) {
  w.write(name, std::span<const std::int64_t>(&value, 1));
}

namespace detail {
template <class T>
T only_value(const std::vector<T>& v, std::string_view name) {
  if (v.size() != 1) {
    throw InputError("state field '" + std::string(name) + "' has " + std::to_string(v.size()) +
                     " values, expected 1");
  }
  return v[0];
}
}  // namespace detail

/// Throws InputError "<what> value k is <v>: a state holds finite numbers only" for the first
/// value that is not finite: a state is checkpoint input, and a NaN would drop out of the
/// comparisons that guard a run (neighbour lists, sparing, grid bounds) instead of failing.
/// `what` names the field as its reader does ("dem state: field 'spheres/x'").
inline void require_finite(std::span<const double> values, std::string_view what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) {
      throw InputError(std::string(what) + " value " + std::to_string(k) + " is " +
                       std::to_string(values[k]) + ": a state holds finite numbers only");
    }
  }
}

/// Reads a field written by write_scalar. Throws InputError naming the field when it is missing,
/// of the other type or not of exactly one value.
[[nodiscard]] inline double read_scalar_f64(const StateReader& r, std::string_view name) {
  return detail::only_value(r.read_f64(name), name);
}
[[nodiscard]] inline std::int64_t read_scalar_i64(const StateReader& r, std::string_view name) {
  return detail::only_value(r.read_i64(name), name);
}

}  // namespace common
