// Shared fixtures of the dem tests: the reference material and packing, the YADE data files.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "common/state_store.hpp"
#include "dem/packing_io.hpp"
#include "dem/params.hpp"
#include "dem/reference_material.hpp"
#include "dem/simulation.hpp"

namespace dem_test {

using dem::reference_material;

inline std::string data_path(const std::string& name) {
  return std::string(MPMXDEM_TEST_DATA "/dem/") + name;
}

/// The reference 1000-sphere YADE packing; its one copy is the one the jobs use.
inline std::string reference_packing_path() {
  return MPMXDEM_SOURCE_DIR "/jobs/packings/packing_N1000_e0.562.txt";
}

inline dem::Packing reference_packing() { return dem::read_packing(reference_packing_path()); }

/// YADE's consolidation of the reference packing with the Hertz-Mindlin reference material
/// (tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py; the packing of
/// jobs/triaxial_dem_hertz_mindlin.toml).
inline dem::Packing hertz_mindlin_packing() {
  return dem::read_packing(MPMXDEM_SOURCE_DIR "/jobs/packings/packing_N1000_hertz_mindlin.txt");
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

/// The columns both two-sphere trajectory tests compare with YADE, from a two-sphere simulation
/// (sphere 1 against sphere 0, rotations theta1 / theta2 about z integrated by the test): x and y
/// of the branch, theta1, theta2, overlap, normal force, shear y and |shear|, rolling moment z
/// and |rolling|, |twist|, kn, ks. `got` must hold at least 13 values; entries 4-12 are left as
/// they are while no contact is active.
inline void measure_pair(const dem::Simulation& sim, double r1, double r2, double theta1,
                         double theta2, std::vector<double>& got) {
  const auto& sp = sim.spheres();
  const auto& c = sim.contacts();
  got[0] = sp.x[1].x() - sp.x[0].x();
  got[1] = sp.x[1].y() - sp.x[0].y();
  got[2] = theta1;
  got[3] = theta2;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (!c.active[p]) continue;
    got[4] = r1 + r2 - c.branch[p].norm();
    got[5] = sim.normal_force(p);
    got[6] = c.hist.shear[1][p];
    got[7] = dem::at(c.hist.shear, p).norm();
    got[8] = c.hist.roll[2][p];
    got[9] = dem::at(c.hist.roll, p).norm();
    got[10] = dem::at(c.hist.twist, p).norm();
    const dem::ContactProps pr = sim.contact_props(p);
    got[11] = pr.kn;
    got[12] = pr.ks;
  }
}

/// A copy of `s` without the fields whose names start with `prefix`.
inline common::StateStore copy_without(const common::StateStore& s, const std::string& prefix) {
  common::StateStore out;
  for (const auto& [name, field] : s.fields()) {
    if (name.rfind(prefix, 0) == 0) continue;
    std::visit([&out, &name](const auto& v) { out.write(name, std::span(v)); }, field);
  }
  return out;
}

}  // namespace dem_test
