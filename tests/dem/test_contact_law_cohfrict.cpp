// Two-sphere golden trajectory against YADE 2023.02a (tests/data/dem/yade_two_sphere_contact.csv)
// and single-contact unit checks of the CohFrict law.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "dem/contact_law_cohfrict.hpp"
#include "dem/simulation.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Vec3;
using dem_test::reference_material;

struct Row {
  long step;
  std::string phase;
  std::vector<double> v;  // x2 .. maxRollPl (15 numbers)
};

std::vector<Row> read_csv(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<Row> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string tok;
    Row r;
    std::getline(ss, tok, ',');
    r.step = std::stol(tok);
    std::getline(ss, r.phase, ',');
    while (std::getline(ss, tok, ',')) r.v.push_back(std::stod(tok));
    rows.push_back(r);
  }
  return rows;
}

TEST(ContactLaw, StiffnessesOfReferencePair) {
  const dem::CohFrictLaw law(reference_material());
  const auto p = law.create(1e-4, 0.7e-4);
  EXPECT_NEAR(p.kn, 2.470588e4, 1e-2);
  EXPECT_NEAR(p.ks, 1.235294e4, 1e-2);
  EXPECT_NEAR(p.kr, 1.729412e-4, 1e-10);
  EXPECT_NEAR(p.roll_cap, 2.1e-5, 1e-18);
  EXPECT_LT(p.twist_cap, 0.0);
}

TEST(ContactLaw, CoulombAndRollingCaps) {
  const dem::CohFrictLaw law(reference_material());
  const auto props = law.create(1e-4, 1e-4);
  dem::CohFrictHistory h{Vec3::UnitX(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const dem::ContactKinematics kin{
      Vec3(1.99e-4, 0, 0), Vec3(0, 10.0, 0), Vec3::Zero(), Vec3(0, 0, 1e4), 1e-4, 1e-4};
  dem::ContactResult res;
  law.apply(props, h, kin, true, 1e-6, res);
  EXPECT_NEAR(res.fn, props.kn * 1e-6, 1e-15);
  EXPECT_NEAR(h.shear.norm(), res.fn * std::tan(M_PI / 6), 1e-15);
  EXPECT_NEAR(h.roll.norm(), 0.3e-4 * res.fn, 1e-18);
  // Newton's third law for forces; torques balance about the contact point.
  EXPECT_NEAR((res.torque1 + res.torque2 + Vec3(1.99e-4, 0, 0).cross(res.force)).norm(), 0.0,
              1e-18);
}

// Tolerance: 1e-8 of the phase maximum of each column; the CSV prints kn, ks, kr with 9 digits
// (5e-9 relative), the forces agree to about 4e-11.
// The YADE trajectory: both spheres have prescribed velocities. Row n holds the contact state
// computed from the positions after step n-1 and the positions after step n.
TEST(ContactLaw, YadeTwoSphereTrajectory) {
  const auto rows = read_csv(dem_test::data_path("yade_two_sphere_contact.csv"));
  ASSERT_EQ(rows.back().step, 73100);
  const double r1 = 1e-4;
  const double r2 = 0.7e-4;
  dem::Spheres s;
  s.add(Vec3::Zero(), r1, 2650.0);
  s.add(Vec3(r1 + r2 + 1e-7, 0, 0), r2, 2650.0);
  s.fixed = {1, 1};
  dem::PeriodicCell cell;
  cell.h = common::Mat3::Identity() * 0.01;
  dem::Simulation sim(s, cell, reference_material(), dem::Numerics{});
  sim.set_dt(1e-9);

  struct Phase {
    Vec3 v2, w1, w2;
  };
  const std::map<std::string, Phase> phases{
      {"A", {Vec3(-1, 0, 0), Vec3::Zero(), Vec3::Zero()}},
      {"B1", {Vec3(0, 1, 0), Vec3::Zero(), Vec3::Zero()}},
      {"B2", {Vec3(0, -1, 0), Vec3::Zero(), Vec3::Zero()}},
      {"B3", {Vec3(0, 1, 0), Vec3::Zero(), Vec3::Zero()}},
      {"C1", {Vec3::Zero(), Vec3(0, 0, -200.0 * r2 / r1), Vec3(0, 0, 200.0)}},
      {"C2", {Vec3::Zero(), Vec3(0, 0, 200.0 * r2 / r1), Vec3(0, 0, -200.0)}}};

  // Columns compared: name, index in Row::v; errors relative to the phase's max |value|.
  const std::vector<std::pair<std::string, int>> cols{
      {"x2", 0},    {"y2", 1},   {"theta1z", 2}, {"theta2z", 3}, {"delta", 4},
      {"Fn", 5},    {"Fs_y", 6}, {"|Fs|", 7},    {"Mb_z", 8},    {"|Mb|", 9},
      {"|Mt|", 10}, {"kn", 11},  {"ks", 12},     {"kr", 13},     {"cap", 14}};
  std::map<std::string, std::vector<double>> phase_max;
  for (const Row& r : rows) {
    auto& mx = phase_max[r.phase];
    mx.resize(cols.size(), 0.0);
    for (std::size_t c = 0; c < cols.size(); ++c)
      mx[c] = std::max(mx[c], std::abs(r.v[cols[c].second]));
  }

  double theta1 = 0.0;
  double theta2 = 0.0;
  std::vector<double> worst(cols.size(), 0.0);
  std::size_t next = 0;
  for (long step = 1; step <= rows.back().step; ++step) {
    // The phase of this step is that of the next recorded row.
    while (rows[next].step < step) ++next;
    const Phase& ph = phases.at(rows[next].phase);
    auto& sp = sim.spheres();
    sp.u[0].setZero();
    sp.u[1] = ph.v2;
    sp.w[0] = ph.w1;
    sp.w[1] = ph.w2;
    sim.compute_forces();
    sim.integrate();
    theta1 += ph.w1.z() * 1e-9;
    theta2 += ph.w2.z() * 1e-9;
    if (rows[next].step != step) continue;
    const Row& r = rows[next];
    const auto& c = sim.contacts();
    double got[15] = {};
    got[0] = sp.x[1].x() - sp.x[0].x();
    got[1] = sp.x[1].y() - sp.x[0].y();
    got[2] = theta1;
    got[3] = theta2;
    for (std::size_t p = 0; p < c.size(); ++p) {
      if (!c.active[p]) continue;
      got[4] = r1 + r2 - c.branch[p].norm();
      got[5] = c.fn[p];
      got[6] = c.hist[p].shear.y();
      got[7] = c.hist[p].shear.norm();
      got[8] = c.hist[p].roll.z();
      got[9] = c.hist[p].roll.norm();
      got[10] = c.hist[p].twist.norm();
      got[11] = c.props[p].kn;
      got[12] = c.props[p].ks;
      got[13] = c.props[p].kr;
      got[14] = c.props[p].roll_cap;
    }
    const auto& mx = phase_max[r.phase];
    for (std::size_t k = 0; k < cols.size(); ++k) {
      const double ref = r.v[cols[k].second];
      const double scale = mx[k] > 0.0 ? mx[k] : 1.0;
      const double err = std::abs(got[cols[k].second] - ref) / scale;
      worst[k] = std::max(worst[k], err);
      ASSERT_LT(err, 1e-8) << "step " << step << " phase " << r.phase << " column " << cols[k].first
                           << ": got " << got[cols[k].second] << " yade " << ref;
    }
  }
  for (std::size_t k = 0; k < cols.size(); ++k) {
    std::cout << "  max relative error (of phase max) " << cols[k].first << ": " << worst[k]
              << "\n";
  }
}

}  // namespace
