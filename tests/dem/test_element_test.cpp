// The drained triaxial element test (dem/element_test.hpp): the inertial time scale, and the
// driver's stopping rule, observer calls and independence of the check interval.
#include "dem/element_test.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "dem/measures.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Mat3;

dem::Simulation small_sample() {
  const dem::Packing pk = dem::read_packing(std::string(MPMXDEM_SOURCE_DIR "/tests/farm/data/packing_N70_seed12.txt"));
  return dem::make_simulation(pk, dem_test::reference_material(), dem::Numerics{});
}

TEST(ElementTest, InertialTimeScale) {
  // d50 sqrt(rho / p) = 2e-4 m * sqrt(2650 / 1e5) s/m = 3.2558e-5 s.
  EXPECT_NEAR(dem::inertial_time(2e-4, 2650.0, 1e5), 3.25576e-5, 1e-10);
  // Four times the pressure halves it; I scales the rate.
  EXPECT_NEAR(dem::inertial_time(2e-4, 2650.0, 4e5), 0.5 * dem::inertial_time(2e-4, 2650.0, 1e5),
              1e-18);
  EXPECT_NEAR(dem::strain_rate(2.5e-4, 2e-4, 2650.0, 1e5), 2.5e-4 / 3.25576e-5, 1e-3);
}

TEST(ElementTest, ServoSettings) {
  dem::DrainedTriaxial t;
  t.axial_rate = 7.0;
  t.confining = 2e5;
  const dem::MixedControl c = dem::triaxial_servo(t);
  EXPECT_EQ(c.l_imposed(2, 2), -7.0);
  EXPECT_EQ(c.max_rate, 70.0);  // the YADE-validated bound, 10 x the axial rate
  EXPECT_TRUE(c.stress_axis[0] && c.stress_axis[1] && !c.stress_axis[2]);
  EXPECT_EQ(c.target[0], -2e5);
}

// Plane strain (biaxial): x held at the confining pressure, y strain-controlled at zero strain,
// z compressed; on the small sample the cell's y size stays exactly the same (L_yy = 0 and no
// shear is imposed, so h_yy is never changed) while sigma_xx follows the servo.
TEST(ElementTest, PlaneStrainHoldsYAndServoesX) {
  dem::DrainedTriaxial t;
  t.axial_rate = 7.0;
  t.confining = 2e5;
  t.plane_strain = true;
  const dem::MixedControl c = dem::triaxial_servo(t);
  EXPECT_TRUE(c.stress_axis[0] && !c.stress_axis[1] && !c.stress_axis[2]);
  EXPECT_EQ(c.l_imposed(1, 1), 0.0);
  EXPECT_EQ(c.l_imposed(2, 2), -7.0);

  dem::Simulation sim = small_sample();
  const double lx0 = sim.cell().h(0, 0);
  const double ly0 = sim.cell().h(1, 1);
  const double lz0 = sim.cell().h(2, 2);
  t.axial_rate = dem::strain_rate(1e-2, 2e-4, 2650.0, 1e5);
  t.confining = 1e5;
  t.eps_end = 2e-3;
  t.check_every = 20;
  dem::run_drained_triaxial(sim, t);
  EXPECT_EQ(sim.cell().h(1, 1), ly0);
  EXPECT_LT(sim.cell().h(2, 2), lz0 * (1.0 - 1.9e-3));
  // The x size moved: the servo acts on it (the 70-sphere sample dilates or contracts laterally).
  EXPECT_NE(sim.cell().h(0, 0), lx0);
}

// Stops at the first check past eps_end; the observer sees every check with the strains of the
// cell since the start, and `last` only on the final call.
TEST(ElementTest, StopsAtTheFirstCheckPastTheTarget) {
  dem::Simulation sim = small_sample();
  const double lz0 = sim.cell().h(2, 2);
  const double v0 = sim.cell().volume();
  const std::int64_t steps0 = sim.steps();
  dem::DrainedTriaxial t;
  t.axial_rate = dem::strain_rate(1e-2, 2e-4, 2650.0, 1e5);
  t.eps_end = 1e-3;
  t.check_every = 20;
  std::vector<dem::TriaxialProgress> seen;
  const auto done = dem::run_drained_triaxial(
      sim, t, [&](const dem::Simulation& s, const dem::TriaxialProgress& now) {
        EXPECT_EQ(s.steps() - steps0, now.steps);
        EXPECT_DOUBLE_EQ(now.eps_a, -std::log(s.cell().h(2, 2) / lz0));
        EXPECT_DOUBLE_EQ(now.eps_v, -std::log(s.cell().volume() / v0));
        seen.push_back(now);
      });
  ASSERT_GE(seen.size(), 2u);
  EXPECT_EQ(done, seen.back().steps);
  EXPECT_EQ(done % 20, 0);
  EXPECT_GE(seen.back().eps_a, 1e-3);
  EXPECT_LT(seen[seen.size() - 2].eps_a, 1e-3);
  for (std::size_t k = 0; k + 1 < seen.size(); ++k) EXPECT_FALSE(seen[k].last);
  EXPECT_TRUE(seen.back().last);
}

// max_steps ends the test short of eps_end; the check interval does not change the trajectory.
TEST(ElementTest, MaxStepsAndCheckIntervalDoNotChangeTheTrajectory) {
  const auto run = [](std::int64_t check_every) {
    dem::Simulation sim = small_sample();
    dem::DrainedTriaxial t;
    t.axial_rate = dem::strain_rate(1e-2, 2e-4, 2650.0, 1e5);
    t.eps_end = 1.0;
    t.check_every = check_every;
    t.max_steps = 150;
    int last_calls = 0;
    EXPECT_EQ(
        dem::run_drained_triaxial(sim, t,
                                  [&](const dem::Simulation&, const dem::TriaxialProgress& now) {
                                    last_calls += now.last ? 1 : 0;
                                  }),
        150);
    EXPECT_EQ(last_calls, 1);
    return sim;
  };
  const dem::Simulation a = run(7);
  const dem::Simulation b = run(150);
  ASSERT_EQ(a.spheres().size(), b.spheres().size());
  const auto bytes = a.spheres().size() * sizeof(common::Vec3);
  EXPECT_EQ(std::memcmp(a.spheres().x.data(), b.spheres().x.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.spheres().u.data(), b.spheres().u.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.cell().h.data(), b.cell().h.data(), sizeof(Mat3)), 0);
  EXPECT_EQ(std::memcmp(a.stress().data(), b.stress().data(), sizeof(Mat3)), 0);
}

}  // namespace
