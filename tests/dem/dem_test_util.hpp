// Shared fixtures of the dem tests: the reference material and packing, the YADE data files.
#pragma once

#include <string>

#include "dem/packing_io.hpp"
#include "dem/params.hpp"
#include "dem/reference_material.hpp"

namespace dem_test {

using dem::reference_material;

inline std::string data_path(const std::string& name) {
  return std::string(MPMXDEM_TEST_DATA) + "/dem/" + name;
}

/// The reference 1000-sphere YADE packing; its one copy is the one the jobs use.
inline std::string reference_packing_path() {
  return std::string(MPMXDEM_SOURCE_DIR) + "/jobs/packings/packing_N1000_e0.562.txt";
}

inline dem::Packing reference_packing() { return dem::read_packing(reference_packing_path()); }

}  // namespace dem_test
