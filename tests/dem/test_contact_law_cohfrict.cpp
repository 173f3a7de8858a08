// Two-sphere golden trajectory against YADE 2023.02a (tests/data/dem/yade_two_sphere_contact.csv)
// and single-contact unit checks of the CohFrict law.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dem/contact_law_cohfrict.hpp"
#include "dem/simulation.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Vec3;
using dem_test::reference_material;

using Row = dem_test::TrajectoryRow;

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
  const auto rows = dem_test::read_trajectory(dem_test::data_path("yade_two_sphere_contact.csv"));
  ASSERT_EQ(rows.back().step, 73100);
  const double r1 = 1e-4;
  const double r2 = 0.7e-4;
  dem::Spheres s;
  s.add(Vec3::Zero(), r1, 2650.0);
  s.add(Vec3(r1 + r2 + 1e-7, 0, 0), r2, 2650.0);
  s.fixed = {1, 1};
  dem::PeriodicCell cell;
  cell.h = common::Mat3::Identity() * 0.01;
  // The fixed skin: positions are compared raw to 1e-8 of each phase's largest value, and y2 is
  // about 1e-23 m in the rotation phases; a list build (the adaptive skin builds early in a cell
  // that barely moves) re-wraps a position into the cell with a round-off of 1e-15 m.
  dem::Numerics num;
  num.skin_min_factor = 0.0;
  dem::Simulation sim(s, cell, reference_material(), num);
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
    std::vector<double> got(15, 0.0);
    dem_test::measure_pair(sim, r1, r2, theta1, theta2, got);
    for (std::size_t p = 0; p < c.size(); ++p) {  // the law's rolling stiffness and cap
      if (!c.active[p]) continue;
      const dem::ContactProps pr = sim.contact_props(p);
      got[13] = pr.kr;
      got[14] = pr.roll_cap;
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

// apply_batch (the force loop's vectorised form, which computes each lane's stiffnesses from its
// radii) against apply() with the properties of create(), bit for bit: random contacts of four
// materials in turn (reference: rolling capped, no twist; twisting on with caps; rolling
// uncapped; no moments), new and old, sliding and sticking, carried over 40 steps of random
// motion, with lanes out of overlap among them (their history untouched, their outputs +0), read
// from and written to the pair arrays at an offset. No tolerance: every output and history double
// must have the same bits (signed zeros included).
TEST(ContactLaw, BatchIsBitIdenticalToApply) {
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto sym = [&](double scale) { return scale * (2.0 * u01(gen) - 1.0); };
  const auto vec = [&](double scale) { return Vec3(sym(scale), sym(scale), sym(scale)); };
  dem::Material twist = reference_material();
  twist.alpha_t = 1.5;
  twist.eta_t = 0.2;
  dem::Material uncapped = reference_material();
  uncapped.eta_r = -1.0;
  dem::Material bare = reference_material();
  bare.alpha_r = 0.0;
  const std::vector<dem::CohFrictLaw> laws{dem::CohFrictLaw(reference_material()),
                                           dem::CohFrictLaw(twist), dem::CohFrictLaw(uncapped),
                                           dem::CohFrictLaw(bare)};
  const auto same = [](double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
  };
  const auto same3 = [&](const Vec3& a, const double(&b)[3][dem::CohFrictBatch::kLanes], int q) {
    return same(a[0], b[0][q]) && same(a[1], b[1][q]) && same(a[2], b[2][q]);
  };
  for (std::size_t m = 0; m < laws.size(); ++m) {
    SCOPED_TRACE("material " + std::to_string(m));
    const dem::CohFrictLaw& law = laws[m];
    const int n = dem::CohFrictBatch::kLanes - 3;  // a partial batch: remainder lanes too
    const std::size_t first = 5;                   // lane q is pair first + q of the arrays
    const auto pair = [&](int q) { return first + static_cast<std::size_t>(q); };
    std::vector<double> tan_phi(first + static_cast<std::size_t>(n), 0.0);
    dem::CohFrictHistoryArrays hist;
    hist.resize(first + static_cast<std::size_t>(n));
    std::vector<double> r1(n), r2(n);
    std::vector<dem::ContactProps> props(n);
    for (int q = 0; q < n; ++q) {
      r1[q] = 1e-4 * (0.5 + u01(gen));
      r2[q] = 1e-4 * (0.5 + u01(gen));
      props[q] = law.create(r1[q], r2[q]);
      tan_phi[pair(q)] = props[q].tan_phi;
    }
    const double dt = 8.5e-8;
    int slides = 0;
    int rolls_capped = 0;
    int twisted = 0;
    int apart = 0;
    common::Mat3 l;
    for (int e = 0; e < 9; ++e) l(e) = sym(50.0);
    for (int step = 0; step < 40; ++step) {
      dem::CohFrictBatch b;
      b.n = n;
      b.first = first;
      std::vector<dem::ContactResult> want(n);
      std::vector<dem::CohFrictHistory> want_hist(n);
      for (int q = 0; q < n; ++q) want_hist[q] = hist.get(pair(q));
      for (int q = 0; q < n; ++q) {
        // Overlap up to 1 % of the radii sum (a gap as large for lanes apart); velocities that
        // make some contacts slide.
        const bool touching = step == 0 || (q + 3 * step) % 7 != 0;
        const double len = (r1[q] + r2[q]) * (1.0 + (touching ? -0.01 : 0.01) * u01(gen));
        const Vec3 d = vec(1.0).normalized() * len;
        const Vec3 du = vec(step % 3 == 0 ? 1.0 : 1e-3);
        const Vec3 w1 = vec(step % 4 == 0 ? 1e3 : 1.0);
        const Vec3 w2 = vec(1e2);
        const bool is_new = step == 0 || (q + step) % 17 == 0;
        if (touching) {
          const dem::ContactKinematics kin{d, du + l * d, w1, w2, r1[q], r2[q]};
          law.apply(props[q], want_hist[q], kin, is_new, dt, want[q]);
        } else {
          want[q] = dem::ContactResult{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.0};
          ++apart;
        }
        for (int a = 0; a < 3; ++a) {
          b.d[a][q] = d[a];
          b.du[a][q] = du[a];
          b.w1[a][q] = w1[a];
          b.w2[a][q] = w2[a];
        }
        b.l2[q] = d.squaredNorm();
        b.r1[q] = r1[q];
        b.r2[q] = r2[q];
        b.touching[q] = touching ? 1 : 0;
        b.fresh[q] = touching && is_new ? 1 : 0;
      }
      law.apply_batch(b, tan_phi, hist, l, dt);
      for (int q = 0; q < n; ++q) {
        const dem::CohFrictHistory got = hist.get(pair(q));
        EXPECT_TRUE(same3(want[q].force, b.force, q)) << "step " << step << " lane " << q;
        EXPECT_TRUE(same3(want[q].torque1, b.torque1, q)) << "step " << step << " lane " << q;
        EXPECT_TRUE(same3(want[q].torque2, b.torque2, q)) << "step " << step << " lane " << q;
        // The normal force is not an output of the batch: Simulation::normal_force computes it
        // from the branch as kn ((r1 + r2) - sqrt(|d|^2)), the same bits as apply().
        const double fn_from_branch =
            b.touching[q] != 0 ? props[q].kn * ((r1[q] + r2[q]) - std::sqrt(b.l2[q])) : 0.0;
        EXPECT_TRUE(same(want[q].fn, fn_from_branch)) << "step " << step << " lane " << q;
        for (int a = 0; a < 3; ++a) {
          EXPECT_TRUE(same(want_hist[q].normal[a], got.normal[a]));
          EXPECT_TRUE(same(want_hist[q].shear[a], got.shear[a]));
          EXPECT_TRUE(same(want_hist[q].roll[a], got.roll[a]));
          EXPECT_TRUE(same(want_hist[q].twist[a], got.twist[a]));
        }
        const double fn = want[q].fn;
        const double roll_cap = props[q].roll_cap;
        slides += fn > 0.0 && got.shear.norm() >= 0.999999 * fn * props[q].tan_phi ? 1 : 0;
        rolls_capped += fn > 0.0 && roll_cap > 0 && got.roll.norm() >= 0.999999 * roll_cap * fn;
        twisted += got.twist.norm() > 0.0 ? 1 : 0;
      }
    }
    // Both sides of the selects were exercised: Coulomb sliding, the rolling cap (materials 0
    // and 1), twisting (material 1 only), lanes apart.
    EXPECT_GT(slides, 0);
    if (m <= 1) {
      EXPECT_GT(rolls_capped, 0);
    }
    if (m == 1) {
      EXPECT_GT(twisted, 0);
    } else {
      EXPECT_EQ(twisted, 0);
    }
    EXPECT_GT(apart, 0);
  }
}

}  // namespace
