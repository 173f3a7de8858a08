// Tests of src/dem/loading.*: the random cloud (binned overlap test) and the check observer of
// equilibrate / prepare.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "dem/loading.hpp"
#include "dem/measures.hpp"
#include "dem_test_util.hpp"

namespace {

// Smallest periodic gap between two spheres of the cloud, over ALL pairs (brute force: the
// reference the binned search of make_cloud must agree with). Negative = overlap.
double smallest_gap(const dem::Packing& pk) {
  const double side = pk.cell.h(0, 0);
  double gap = 1e300;
  for (std::size_t a = 0; a < pk.x.size(); ++a) {
    for (std::size_t b = a + 1; b < pk.x.size(); ++b) {
      common::Vec3 d = pk.x[a] - pk.x[b];
      for (int k = 0; k < 3; ++k) d[k] -= side * std::round(d[k] / side);
      gap = std::min(gap, d.norm() - pk.r[a] - pk.r[b]);
    }
  }
  return gap;
}

dem::Psd wide_psd() {  // diameters 1 to 4 mm: the large spheres set the bin width
  dem::Psd psd;
  psd.diameter = {1e-3, 2e-3, 4e-3};
  psd.passing = {0.0, 0.5, 1.0};
  return psd;
}

// 3000 spheres: the cell is about 11 largest diameters wide, so the candidates are tested against
// the 27 bins around them only. Every pair (4.5 million) is checked here.
TEST(Loading, CloudHasNoOverlapWithManyBins) {
  const dem::Packing pk = dem::make_cloud(wide_psd(), 3000, 0.3, 7);
  ASSERT_EQ(pk.x.size(), 3000u);
  const double side = pk.cell.h(0, 0);
  const double r_max = *std::max_element(pk.r.begin(), pk.r.end());
  EXPECT_GE(side / (2.0 * r_max), 3.0);  // the binned path, not the single-bin one
  EXPECT_GT(smallest_gap(pk), 0.0);
  for (const common::Vec3& x : pk.x) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(x[k], 0.0);
      EXPECT_LT(x[k], side);
    }
  }
}

// A handful of spheres: fewer than 3 bins per side, one bin holds them all.
TEST(Loading, CloudHasNoOverlapInASingleBin) {
  const dem::Packing pk = dem::make_cloud(wide_psd(), 6, 0.3, 3);
  ASSERT_EQ(pk.x.size(), 6u);
  const double r_max = *std::max_element(pk.r.begin(), pk.r.end());
  EXPECT_LT(pk.cell.h(0, 0) / (2.0 * r_max), 3.0);
  EXPECT_GT(smallest_gap(pk), 0.0);
}

TEST(Loading, CloudIsDeterministicForASeed) {
  const dem::Packing a = dem::make_cloud(wide_psd(), 500, 0.3, 11);
  const dem::Packing b = dem::make_cloud(wide_psd(), 500, 0.3, 11);
  const dem::Packing c = dem::make_cloud(wide_psd(), 500, 0.3, 12);
  ASSERT_EQ(a.x.size(), b.x.size());
  for (std::size_t i = 0; i < a.x.size(); ++i) {
    EXPECT_EQ(a.x[i], b.x[i]);
    EXPECT_EQ(a.r[i], b.r[i]);
  }
  EXPECT_NE(a.x[0], c.x[0]);
}

// equilibrate calls the observer once per check (check_every steps), with the state it measures.
TEST(Loading, EquilibrateCallsTheObserverAtEveryCheck) {
  dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                             dem_test::reference_material(), dem::Numerics{});
  dem::EquilibriumTarget t;
  t.pressure = 1e5;
  t.stress_tol = 0.01;
  t.unbalanced_tol = 0.05;
  t.check_every = 50;
  std::int64_t calls = 0;
  std::int64_t last_steps = -1;
  double last_p = 0.0;
  const std::int64_t steps =
      dem::equilibrate(sim, t, [&](const dem::Simulation& s, const dem::Measures& m) {
        ++calls;
        last_steps = s.steps();
        last_p = m.p;
      });
  EXPECT_GT(calls, 0);
  EXPECT_EQ(calls * t.check_every, steps);
  EXPECT_EQ(last_steps, sim.steps());
  EXPECT_EQ(last_p, dem::measure(sim).p);
}

// A tolerance no packing reaches: a numerical failure that says which criterion failed, each
// with its value and tolerance.
TEST(Loading, EquilibrateFailureNamesTheCriterionAndItsTolerance) {
  dem::Simulation sim = dem::make_simulation(dem_test::reference_packing(),
                                             dem_test::reference_material(), dem::Numerics{});
  dem::EquilibriumTarget t;
  t.unbalanced_tol = 1e-300;
  t.check_every = 50;
  t.max_steps = 200;
  try {
    (void)dem::equilibrate(sim, t);
    FAIL() << "no error";
  } catch (const common::NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("not reached in 200 steps"), std::string::npos) << what;
    EXPECT_NE(what.find("(tolerance 1e-300)"), std::string::npos) << what;
    EXPECT_NE(what.find("(tolerance 0.01)"), std::string::npos) << what;
    EXPECT_NE(what.find(" contacts"), std::string::npos) << what;
  }
}

}  // namespace
