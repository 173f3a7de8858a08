// Numbers and vectors in error messages (solver.cpp, solver_config.cpp): every digit where a
// value must be reproducible (num_str, vec_str), the shortest form where it echoes a job's value.
#pragma once

#include <sstream>
#include <string>

#include "common/types.hpp"

namespace mpm::messages {

inline std::string vec_str(const common::Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return s.str();
}

inline std::string num_str(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

inline std::string short_str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace mpm::messages
