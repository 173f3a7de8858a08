// Shared fixtures of the dem tests: the reference material and packing.
#pragma once

#include <string>

#include "dem/packing_io.hpp"
#include "dem/params.hpp"

namespace dem_test {

/// Placeholder parameters of the reference README (section 7).
inline dem::Material reference_material() {
  dem::Material m;
  m.density = 2650.0;
  m.young = 3e8;
  m.ks_over_kn = 0.5;
  m.friction_deg = 30.0;
  m.alpha_r = 2.0;
  m.eta_r = 0.3;
  m.alpha_t = 0.0;
  m.eta_t = -1.0;
  return m;
}

inline std::string data_path(const std::string& name) {
  return std::string(MPMXDEM_TEST_DATA) + "/dem/" + name;
}

inline dem::Packing reference_packing() {
  return dem::read_packing(data_path("packing_N1000_e0.562.txt"));
}

}  // namespace dem_test
