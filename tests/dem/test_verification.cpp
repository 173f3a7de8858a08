// Verification (slower): drained triaxial on the reference packing against YADE's CSV for the
// first 1 % of axial strain; compaction of a small random sample to the target pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "dem/element_test.hpp"
#include "dem/loading.hpp"
#include "dem/measures.hpp"
#include "dem_test_util.hpp"

namespace {

struct YadeRow {
  double eps_a, eps_v, p, q;
};

std::vector<YadeRow> read_yade(const std::string& file = "yade_triax_N1000_I2.5e-4.csv") {
  std::ifstream in(dem_test::data_path(file));
  EXPECT_TRUE(in.good());
  std::vector<YadeRow> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<double> v;
    std::string tok;
    while (std::getline(ss, tok, ',')) v.push_back(std::stod(tok));
    rows.push_back({v[3], v[4], v[5], v[6]});
  }
  return rows;
}

// Linear interpolation of YADE's (eps_a -> value) at eps.
double interp(const std::vector<YadeRow>& rows, double eps, double YadeRow::*field) {
  for (std::size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].eps_a >= eps) {
      const double t = (eps - rows[k - 1].eps_a) / (rows[k].eps_a - rows[k - 1].eps_a);
      return rows[k - 1].*field + t * (rows[k].*field - rows[k - 1].*field);
    }
  }
  return rows.back().*field;
}

// The reference packing re-equilibrated at 100 kPa (its file holds no shear forces).
dem::Simulation equilibrated_reference(const dem::Packing& packing = dem_test::reference_packing(),
                                       const dem::Material& material =
                                           dem_test::reference_material()) {
  dem::Simulation sim = dem::make_simulation(packing, material, dem::Numerics{});
  dem::EquilibriumTarget et;
  et.stress_tol = 0.005;
  et.unbalanced_tol = 0.005;
  dem::equilibrate(sim, et);
  return sim;
}

// The largest differences from YADE's series over a drained triaxial of `sim` at I = 2.5e-4 (axial
// rate I / t_ref, t_ref = d50 sqrt(rho / p0)), lateral stress servo-controlled at 100 kPa, to 1 %
// axial strain: |q/p - YADE|, |eps_v - YADE| and, after the first 0.1 % (the servo needs it to
// pick up the lateral rate: 1.3 % overshoot at the first sample), |sigma_r - 100 kPa| / 100 kPa.
struct FirstPercent {
  double eps_a = 0.0, qp = 0.0, eps_v = 0.0, lateral = 0.0;
};
FirstPercent first_percent_against(dem::Simulation& sim, const std::vector<YadeRow>& yade) {
  dem::DrainedTriaxial test;
  test.axial_rate = dem::strain_rate(2.5e-4, 2e-4, 2650.0, 1e5);  // d50 of YADE's packing
  test.confining = 1e5;
  test.eps_end = 0.01;
  test.check_every = 400;
  FirstPercent w;
  dem::run_drained_triaxial(
      sim, test, [&](const dem::Simulation& s, const dem::TriaxialProgress& now) {
        w.eps_a = now.eps_a;
        const auto& sigma = s.stress();
        const double sa = -sigma(2, 2);
        const double sr = -0.5 * (sigma(0, 0) + sigma(1, 1));
        const double qp = (sa - sr) / dem::pressure(sigma);
        const double qp_y = interp(yade, w.eps_a, &YadeRow::q) / interp(yade, w.eps_a, &YadeRow::p);
        w.qp = std::max(w.qp, std::abs(qp - qp_y));
        w.eps_v = std::max(w.eps_v, std::abs(now.eps_v - interp(yade, w.eps_a, &YadeRow::eps_v)));
        if (w.eps_a > 0.001) w.lateral = std::max(w.lateral, std::abs(sr - 1e5) / 1e5);
      });
  std::cout << "  to eps_a = " << w.eps_a << ": max |q/p - yade| = " << w.qp
            << ", max |eps_v - yade| = " << w.eps_v
            << ", max |sigma_r - 100 kPa| / 100 kPa = " << w.lateral << "\n";
  return w;
}

// The CohFrict law on the reference packing. The packing file carries no shear
// forces, so the sample is first re-equilibrated at 100 kPa: the start differs from YADE's in the
// contact history, which bounds how close the curves can be. Tolerances: |q/p - YADE| <= 0.03
// (1.5 % of the peak 2.04), |eps_v - YADE| <= 2e-4 (8 % of its maximum 2.4e-3 in this range),
// lateral stress within 1 % of 100 kPa after 0.1 % axial strain. Measured: see the printed maxima
// (docs/design/dem.md).
TEST(Verification, DrainedTriaxialFirstPercentMatchesYade) {
  dem::Simulation sim = equilibrated_reference();
  const FirstPercent w = first_percent_against(sim, read_yade());
  EXPECT_GE(w.eps_a, 0.01);
  EXPECT_LT(w.qp, 0.03);
  EXPECT_LT(w.eps_v, 2e-4);
  EXPECT_LT(w.lateral, 0.01);
}

// The same with the Hertz-Mindlin law (jobs/triaxial_dem_hertz_mindlin.toml's material) on YADE's
// packing consolidated with that law, against YADE's own triaxial of it
// (tools/mpmxdem_tools/references/yade_triax_hertz_mindlin.py; the whole curve in docs/validation/yade_element_test.md).
// The same tolerances as the CohFrict law's; measured: max |q/p - YADE| 0.008, |eps_v - YADE| 1.5e-5,
// lateral stress within 3e-5.
TEST(Verification, HertzMindlinDrainedTriaxialFirstPercentMatchesYade) {
  dem::Simulation sim = equilibrated_reference(dem_test::hertz_mindlin_packing(),
                                               dem::hertz_mindlin_reference_material());
  const FirstPercent w =
      first_percent_against(sim, read_yade("yade_triax_hertz_mindlin_N1000_I2.5e-4.csv"));
  EXPECT_GE(w.eps_a, 0.01);
  EXPECT_LT(w.qp, 0.03);
  EXPECT_LT(w.eps_v, 2e-4);
  EXPECT_LT(w.lateral, 0.01);
}

// The lateral servo at the coupling's rates (docs/design/dem.md, "Stress control"): drained
// triaxial of the reference packing at I = 1e-3 and 1e-2 to 3 %, sigma_xx and sigma_yy checked
// every 20 steps from 0.05 % on. Tolerance 2 % (the stress path a reference needs; the run's
// guard, dem.loading.lateral_tolerance, is 5 %). Measured to 10 %: max 0.08 % and 0.78 % (the
// former servo, tau = 200 steps without feed-forward, lost it by 6 % and 17 % at 0.1 %).
TEST(Verification, DrainedTriaxialHoldsTheLateralStressAtFastRates) {
  for (const double inertial : {1e-3, 1e-2}) {
    dem::Simulation sim = equilibrated_reference();
    dem::DrainedTriaxial test;
    test.axial_rate = dem::strain_rate(inertial, 2e-4, 2650.0, 1e5);
    test.confining = 1e5;
    test.eps_end = 0.03;
    test.check_every = 20;
    double worst = 0.0;
    double eps_a = 0.0;
    dem::run_drained_triaxial(sim, test,
                              [&](const dem::Simulation& s, const dem::TriaxialProgress& now) {
                                eps_a = now.eps_a;
                                if (eps_a < 5e-4) return;
                                for (int a = 0; a < 2; ++a) {
                                  worst = std::max(worst, std::abs(-s.stress()(a, a) - 1e5) / 1e5);
                                }
                              });
    std::cout << "  I = " << inertial << ", to eps_a = " << eps_a
              << ": max |sigma_xx, sigma_yy - 100 kPa| / 100 kPa = " << worst << "\n";
    EXPECT_GE(eps_a, 0.03);
    EXPECT_LT(worst, 0.02) << "I = " << inertial;
  }
}

// Random cloud from the reference PSD (linear mass passing between 0.65 and 1.35 d50), isotropic
// compaction at 1 degree friction, friction restored to 30 degrees, re-equilibration. The loop's
// exit condition (every axis within 1 % of 100 kPa, unbalanced force below 1 %) is checked, and
// what it does not guarantee: the state it reaches.
// - Physically: a near-frictionless compaction reaches random close packing. Seeds 42-46 and two
//   1-ulp changes of the compaction rate (below) give e = 0.562-0.607 and Z without rattlers
//   Zm = 5.79-6.02, near the isostatic 6: the bands [0.55, 0.62] and [5.7, 6.1].
// - As stored for seed 42: e = 0.575341815986355, 545 contacts (Z = 5.45), 122,200 steps (since
//   the Verlet skin default became 0.1 r_max; at 0.15: 0.583351332865679, 584, 114,000). The
//   trajectory is chaotic: changing the compaction rate by one ulp (20 +/- 4e-15) gives
//   e = 0.5818 / 0.5618 and 565 / 579 contacts. So a tolerance of 1e-12 on e and the exact counts
//   fail on any change of the arithmetic of DEM (intended or not); the values hold for builds
//   without FMA contraction (the default: MPMXDEM_NATIVE=OFF), so that part is skipped under
//   __FMA__. A change of results made on purpose updates these values, and says so.
TEST(Verification, CompactionReachesTargetPressure) {
  dem::Psd psd;
  psd.diameter = {0.65 * 2e-4, 1.35 * 2e-4};
  psd.passing = {0.0, 1.0};
  const dem::Packing cloud = dem::make_cloud(psd, 200, 0.3, 42);
  EXPECT_EQ(cloud.r.size(), 200u);
  dem::Simulation sim =
      dem::make_simulation(cloud, dem_test::reference_material(), dem::Numerics{});
  dem::Preparation prep;
  prep.friction_comp_deg = 1.0;
  prep.target.pressure = 1e5;
  prep.target.stress_tol = 0.01;
  prep.target.unbalanced_tol = 0.01;
  prep.compaction_rate = 20.0;
  const auto steps = dem::prepare(sim, prep).steps;
  const auto m = dem::measure(sim);
  std::cout << std::setprecision(15) << "  compaction: " << steps << " steps, p = " << m.p
            << " Pa, e = " << m.void_ratio << ", Z = " << m.z << " (" << m.n_contacts
            << " contacts), Zm = " << m.z_mech << ", unbalanced = " << m.unbalanced << "\n";
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(-m.stress(a, a), 1e5, 1e3);
  EXPECT_NEAR(m.p, 1e5, 1e3);
  EXPECT_LT(m.unbalanced, 0.01);
  EXPECT_NEAR(std::tan(30.0 * M_PI / 180.0), sim.contacts().tan_phi[0], 1e-12);
  EXPECT_GE(m.void_ratio, 0.55);
  EXPECT_LE(m.void_ratio, 0.62);
  EXPECT_GE(m.z_mech, 5.7);
  EXPECT_LE(m.z_mech, 6.1);
#ifndef __FMA__
  EXPECT_EQ(steps, 122200);
  EXPECT_EQ(m.n_contacts, 545);
  EXPECT_NEAR(m.void_ratio, 0.575341815986355, 1e-12);
#endif
}

}  // namespace
