// The Hertz-Mindlin law against YADE 2023.02a: the coefficients of one pair and a two-sphere
// golden trajectory (tests/data/dem/yade_hertz_mindlin_pair.csv, written by
// tools/mpmxdem_tools/references/yade_hertz_mindlin_pair.py: normal loading, sliding back and forth, rolling to the cap and
// back, twisting), run through Simulation (the force loop's batched law).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "dem/contact_law.hpp"
#include "dem/loading.hpp"
#include "dem/simulation.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Vec3;

// The material of tools/mpmxdem_tools/references/yade_hertz_mindlin_pair.py.
dem::Material yade_pair_material() {
  dem::Material m;
  m.law = dem::ContactLawKind::hertz_mindlin;
  m.density = 2650.0;
  m.young = 3e8;
  m.friction_deg = 30.0;
  m.hm.poisson = 0.25;
  m.hm.krot = 2e-5;
  m.hm.ktwist = 1e-5;
  m.hm.eta = 0.3;
  return m;
}

using Row = dem_test::TrajectoryRow;

// Ip2_FrictMat_FrictMat_MindlinPhys by hand for R1 = 1e-4, R2 = 0.7e-4, E = 3e8, nu = 0.25:
// E* = E / (2 (1 - nu^2)) = 1.6e8, R* = 4.1176e-5, kno = 4/3 E* sqrt(R*); G = 1.2e8,
// kso = 2 sqrt(4 R*) G / (2 - nu); the bending cap 0.3 (R1 + R2) / 2 = 2.55e-5 m.
TEST(ContactLawHertzMindlin, CoefficientsOfTheYadePair) {
  const dem::Material m = yade_pair_material();
  const double r_star = 1e-4 * 0.7e-4 / 1.7e-4;
  const auto k = dem::hertz_mindlin_coefficients(m, 1e-4, 0.7e-4);
  EXPECT_NEAR(k.kno, 4.0 / 3.0 * 1.6e8 * std::sqrt(r_star), 1e-9 * k.kno);
  EXPECT_NEAR(k.kso, 2.0 * std::sqrt(4.0 * r_star) * 1.2e8 / 1.75, 1e-9 * k.kso);
  EXPECT_NEAR(k.roll_cap, 2.55e-5, 1e-18);
  // eta = 0: no cap (YADE's convention), not a zero cap.
  dem::Material uncapped = m;
  uncapped.hm.eta = 0.0;
  EXPECT_LT(dem::hertz_mindlin_coefficients(uncapped, 1e-4, 0.7e-4).roll_cap, 0.0);
  // The tangent stiffnesses at an overlap, as YADE's MindlinPhys stores them.
  const dem::ContactLaw law(m);
  const dem::ContactProps p = law.props(1e-4, 0.7e-4, 1e-6, 0.5);
  EXPECT_NEAR(p.kn, 1.5 * k.kno * 1e-3, 1e-12 * p.kn);
  EXPECT_NEAR(p.ks, k.kso * 1e-3, 1e-12 * p.ks);
  EXPECT_EQ(p.kr, 2e-5);
  EXPECT_EQ(p.kt, 1e-5);
  EXPECT_LT(p.twist_cap, 0.0);
  EXPECT_NEAR(law.normal_force(1e-4, 0.7e-4, 1e-6), k.kno * 1e-9, 1e-12 * k.kno * 1e-9);
}

// Tolerance: 1e-8 of the phase maximum of each column, as for the CohFrict trajectory. YADE
// computes delta^1.5 with pow and the shear increment as (v_s dt / dt) dt; we compute delta
// sqrt(delta) and v_s dt: round-off apart (about 1e-12 here), the same law.
TEST(ContactLawHertzMindlin, YadeTwoSphereTrajectory) {
  const auto rows = dem_test::read_trajectory(dem_test::data_path("yade_hertz_mindlin_pair.csv"));
  ASSERT_EQ(rows.back().step, 93100);
  const double r1 = 1e-4;
  const double r2 = 0.7e-4;
  dem::Spheres s;
  s.add(Vec3::Zero(), r1, 2650.0);
  s.add(Vec3(r1 + r2 + 1e-7, 0, 0), r2, 2650.0);
  s.fixed = {1, 1};
  dem::PeriodicCell cell;
  cell.h = common::Mat3::Identity() * 0.01;
  dem::Numerics num;
  num.skin_min_factor = 0.0;  // the fixed skin (see the CohFrict trajectory)
  dem::Simulation sim(s, cell, yade_pair_material(), num);
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
      {"C2", {Vec3::Zero(), Vec3(0, 0, 200.0 * r2 / r1), Vec3(0, 0, -200.0)}},
      {"D", {Vec3::Zero(), Vec3(-100.0, 0, 0), Vec3(100.0, 0, 0)}}};
  const std::vector<std::string> names{"x2",  "y2",   "theta1z", "theta2z", "delta",
                                       "Fn",  "Fs_y", "|Fs|",    "Mb_z",    "|Mb|",
                                       "|Mt|", "kn",  "ks"};
  std::map<std::string, std::vector<double>> phase_max;
  for (const Row& r : rows) {
    auto& mx = phase_max[r.phase];
    mx.resize(names.size(), 0.0);
    for (std::size_t c = 0; c < names.size(); ++c) mx[c] = std::max(mx[c], std::abs(r.v[c]));
  }

  double theta1 = 0.0;
  double theta2 = 0.0;
  std::vector<double> worst(names.size(), 0.0);
  std::size_t next = 0;
  bool slid = false;
  bool capped = false;
  for (long step = 1; step <= rows.back().step; ++step) {
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
    std::vector<double> got(names.size(), 0.0);
    dem_test::measure_pair(sim, r1, r2, theta1, theta2, got);
    for (std::size_t p = 0; p < c.size(); ++p) {  // Coulomb sliding and the bending cap reached
      if (!c.active[p]) continue;
      slid = slid || got[7] >= 0.999999 * got[5] * std::tan(std::numbers::pi / 6.0);
      capped = capped || got[9] >= 0.999999 * 2.55e-5 * got[5];
    }
    const auto& mx = phase_max[r.phase];
    for (std::size_t k = 0; k < names.size(); ++k) {
      const double scale = mx[k] > 0.0 ? mx[k] : 1.0;
      const double err = std::abs(got[k] - r.v[k]) / scale;
      worst[k] = std::max(worst[k], err);
      ASSERT_LT(err, 1e-8) << "step " << step << " phase " << r.phase << " column " << names[k]
                           << ": got " << got[k] << " yade " << r.v[k];
    }
  }
  // The trajectory went through Coulomb sliding and the bending cap.
  EXPECT_TRUE(slid);
  EXPECT_TRUE(capped);
  for (std::size_t k = 0; k < names.size(); ++k) {
    std::cout << "  max relative error (of phase max) " << names[k] << ": " << worst[k] << "\n";
  }
}

// YADE's Hertz-Mindlin packing with its material: steps run, contacts carry
// Hertzian forces (Simulation::normal_force = kno delta^1.5), the critical time step comes from
// the tangent stiffnesses (finite, positive) and the results do not depend on the thread count.
TEST(ContactLawHertzMindlin, PackingStepsAndThreadCountInvariance) {
  const dem::Packing pk = dem_test::hertz_mindlin_packing();
  const dem::Material m = dem::hertz_mindlin_reference_material();
  const int saved = omp_get_max_threads();
  const auto run = [&](int threads) {
    omp_set_num_threads(threads);
    dem::Simulation sim = dem::make_simulation(pk, m, dem::Numerics{});
    sim.compute_forces();
    sim.refresh_dt();
    for (int i = 0; i < 200; ++i) sim.step();
    omp_set_num_threads(saved);
    return sim;
  };
  const dem::Simulation a = run(1);
  const dem::Simulation b = run(2);
  EXPECT_GT(a.dt(), 0.0);
  EXPECT_TRUE(std::isfinite(a.dt()));
  std::size_t active = 0;
  for (std::size_t p = 0; p < a.contacts().size(); ++p) {
    if (!a.contacts().active[p]) continue;
    ++active;
    const auto& s = a.spheres();
    const double ri = s.r[static_cast<std::size_t>(a.contacts().i[p])];
    const double rj = s.r[static_cast<std::size_t>(a.contacts().j[p])];
    const double delta = ri + rj - a.contacts().branch[p].norm();
    const auto k = dem::hertz_mindlin_coefficients(m, ri, rj);
    EXPECT_NEAR(a.normal_force(p), k.kno * std::pow(delta, 1.5), 1e-12 * a.normal_force(p));
  }
  EXPECT_GT(active, 100u);
  for (int e = 0; e < 9; ++e) EXPECT_EQ(a.stress()(e), b.stress()(e));
  for (std::size_t i = 0; i < a.spheres().size(); ++i) EXPECT_EQ(a.spheres().x[i], b.spheres().x[i]);
}

}  // namespace
