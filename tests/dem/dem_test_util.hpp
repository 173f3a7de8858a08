// Shared fixtures of the dem tests: the reference material and packing, the YADE data files.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

/// YADE's consolidation of the reference packing with the Hertz-Mindlin reference material
/// (tools/yade_triax_hertz_mindlin.py; the packing of jobs/triaxial_dem_hertz_mindlin.toml).
inline dem::Packing hertz_mindlin_packing() {
  return dem::read_packing(std::string(MPMXDEM_SOURCE_DIR) +
                           "/jobs/packings/packing_N1000_hertz_mindlin.txt");
}

/// A row of a YADE two-sphere trajectory (tests/data/dem/yade_*pair*.csv, yade_two_sphere_*):
/// step, phase, then the numbers of the other columns.
struct TrajectoryRow {
  long step;
  std::string phase;
  std::vector<double> v;
};

inline std::vector<TrajectoryRow> read_trajectory(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<TrajectoryRow> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string tok;
    TrajectoryRow r;
    std::getline(ss, tok, ',');
    r.step = std::stol(tok);
    std::getline(ss, r.phase, ',');
    while (std::getline(ss, tok, ',')) r.v.push_back(std::stod(tok));
    rows.push_back(r);
  }
  return rows;
}

}  // namespace dem_test
