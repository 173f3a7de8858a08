// Shared fixtures of the dem tests: the reference material and packing.
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

inline dem::Packing reference_packing() {
  return dem::read_packing(data_path("packing_N1000_e0.562.txt"));
}

}  // namespace dem_test
