// dem::free_flight_holds (no pair can come into contact within a step) and the RVE step it
// allows (RveParams::free_flight: one DEM step of the whole T_p for an RVE without contacts).
#include "dem/free_flight.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "common/state_store.hpp"
#include "dem/loading.hpp"
#include "dem/rve.hpp"
#include "dem_test_util.hpp"
#include "former_state.hpp"

namespace {

using common::Mat3;
using common::Vec3;

bool same_bits(const Mat3& a, const Mat3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Mat3)) == 0;
}

// Two spheres of radius 0.1 mm in a 1 mm cube, 5 um apart along x (inside the 10 um skin).
dem::Simulation two_spheres() {
  dem::Packing pk;
  pk.cell.h = Mat3::Identity() * 1e-3;
  pk.x = {Vec3(4e-4, 5e-4, 5e-4), Vec3(6.05e-4, 5e-4, 5e-4)};
  pk.r = {1e-4, 1e-4};
  dem::Numerics num;
  num.skin_min_factor = 0.0;
  return dem::make_simulation(pk, dem_test::reference_material(), num);
}

// Closing at 1 m/s, the gap of 5 um closes after 5 us: a step of 4 us is free flight, one of
// 6 us is not. A sphere passing by at an offset touches in the middle of a step whose two ends
// are apart: the closest approach is found, not only the ends.
TEST(FreeFlight, APairThatTouchesWithinTheStepIsFound) {
  dem::Simulation sim = two_spheres();
  ASSERT_EQ(sim.contacts().size(), 1u);  // the pair is listed, not in contact
  ASSERT_EQ(sim.contacts().active[0], 0);
  sim.spheres().u[1] = Vec3(-1.0, 0.0, 0.0);
  const Mat3 l = Mat3::Zero();
  EXPECT_TRUE(dem::free_flight_holds(sim, 4e-6, l, 1e-12));
  EXPECT_FALSE(dem::free_flight_holds(sim, 6e-6, l, 1e-12));
  // An affine compression that closes the same gap: L_xx = -1 / (2.05e-4 s) moves the second
  // sphere at -1 m/s relative to the first.
  sim.spheres().u[1] = Vec3::Zero();
  Mat3 lc = Mat3::Zero();
  lc(0, 0) = -1.0 / 2.05e-4;
  EXPECT_TRUE(dem::free_flight_holds(sim, 4e-6, lc, 1e-12));
  EXPECT_FALSE(dem::free_flight_holds(sim, 6e-6, lc, 1e-12));
  // Passing by: 2 um below the line of centres at a distance of 5 nm less than the radii's sum,
  // moving up by 4 um over 20 us: 5 nm apart at both ends of the step, 5 nm of overlap in its
  // middle (and within half the skin of its start: the list still holds).
  constexpr double kClosest = 2e-4 - 5e-9;
  sim.spheres().x[1] = Vec3(4e-4 + kClosest, 5e-4 - 2e-6, 5e-4);
  sim.spheres().u[1] = Vec3(0.0, 0.2, 0.0);
  sim.invalidate_neighbors();
  sim.compute_forces();  // the list of the new positions
  ASSERT_EQ(sim.contacts().size(), 1u);
  ASSERT_EQ(sim.contacts().active[0], 0);
  const Vec3 end = sim.spheres().x[1] + 2e-5 * sim.spheres().u[1] - sim.spheres().x[0];
  ASSERT_GT(end.norm(), 2e-4);
  EXPECT_FALSE(dem::free_flight_holds(sim, 2e-5, l, 1e-12));
  EXPECT_TRUE(dem::free_flight_holds(sim, 2e-6, l, 1e-12));
}

// A pair in contact, or a list that is not current, is never free flight.
TEST(FreeFlight, AContactOrAStaleListIsNotFreeFlight) {
  dem::Simulation sim = two_spheres();
  sim.spheres().u[1] = Vec3(1.0, 0.0, 0.0);  // moving apart
  EXPECT_TRUE(dem::free_flight_holds(sim, 1e-6, Mat3::Zero(), 1e-12));
  sim.invalidate_neighbors();
  EXPECT_FALSE(dem::free_flight_holds(sim, 1e-6, Mat3::Zero(), 1e-12));
  sim.spheres().x[1] = Vec3(5.9e-4, 5e-4, 5e-4);  // 10 um overlap
  sim.compute_forces();
  ASSERT_EQ(sim.contacts().active[0], 1);
  EXPECT_FALSE(dem::free_flight_holds(sim, 1e-12, Mat3::Zero(), 1e-12));
  // A sphere that would leave the list's reach within the step: the drift measure at the end.
  dem::Simulation far = two_spheres();
  far.spheres().u[0] = Vec3(0.0, 0.0, 100.0);  // 10 um in 0.1 us: beyond half the skin
  EXPECT_TRUE(dem::free_flight_holds(far, 1e-9, Mat3::Zero(), 1e-12));
  EXPECT_FALSE(dem::free_flight_holds(far, 1e-7, Mat3::Zero(), 1e-12));
}

dem::RveParams rve_params(bool free_flight) {
  dem::RveParams p;
  p.material = dem_test::reference_material();
  p.inertial_number = 1e-2;
  p.rate = dem::RveRate::material;
  p.contact_loss = dem::ContactLoss::strained;
  p.free_flight = free_flight;
  return p;
}

// The reference packing dilated until it has no contact, and then some (strained: the cell
// follows). Made once for the tests that start from it.
dem::Simulation make_contact_free_state() {
  dem::Rve rve(dem_test::reference_packing(), rve_params(false));
  dem::StepReport r;
  for (int k = 0; k < 200 && (r.guards & dem::kGuardNoContacts) == 0; ++k) {
    r = rve.step(Mat3::Identity() * 1e3, 2e-6);
  }
  EXPECT_NE(r.guards & dem::kGuardNoContacts, 0u) << "the packing did not come apart";
  // 20 more: 4 % more volume, the neighbours' gaps opened by about 1 % of a diameter.
  for (int k = 0; k < 20; ++k) r = rve.step(Mat3::Identity() * 1e3, 2e-6);
  EXPECT_NE(r.guards & dem::kGuardNoContacts, 0u);
  return rve.simulation();
}

const dem::Simulation& contact_free_state() {
  static const dem::Simulation state = make_contact_free_state();
  return state;
}

// Without contacts, an increment in which no pair can touch runs as one DEM step; the spheres
// and the cell end where the n stepped DEM steps put them, to O(|L dt|^2) (the one step is
// first order in L, the n steps a product of n factors), and the velocities, under no force,
// are unchanged in both.
TEST(FreeFlight, OneStepMovesAContactFreeRveAsItsStepsDo) {
  const dem::Simulation& state = contact_free_state();
  dem::Rve stepped = dem::Rve::from_simulation(state, rve_params(false));
  dem::Rve one = dem::Rve::from_simulation(state, rve_params(true));
  Mat3 l = Mat3::Zero();
  l(0, 2) = 2e2;  // simple shear and a compression, 8e-5 and 2e-5 over the step
  l(2, 2) = -5e1;
  // Shorter than the 0.67 us in which the first pair (110 nm apart, closing at 0.16 m/s) touches.
  const double dt = 4e-7;
  const dem::StepReport a = stepped.step(l, dt);
  const dem::StepReport b = one.step(l, dt);
  std::printf("stepped: %lld DEM steps; free flight: %lld\n", static_cast<long long>(a.dem_steps),
              static_cast<long long>(b.dem_steps));
  ASSERT_GT(a.dem_steps, 1);
  EXPECT_EQ(a.guards & dem::kGuardFreeFlight, 0u);
  ASSERT_NE(b.guards & dem::kGuardFreeFlight, 0u);
  EXPECT_EQ(b.dem_steps, 1);
  EXPECT_EQ(b.t_p, a.t_p);
  EXPECT_NE(b.guards & dem::kGuardNoContacts, 0u);
  EXPECT_EQ(one.stress().norm(), 0.0);
  const auto& sa = stepped.simulation().spheres();
  const auto& sb = one.simulation().spheres();
  const double size = std::cbrt(state.cell().h.determinant());
  double dx = 0.0;
  for (std::size_t q = 0; q < sa.size(); ++q) {
    dx = std::max(dx, (sa.x[q] - sb.x[q]).norm());
    ASSERT_EQ(sa.u[q], sb.u[q]) << "sphere " << q;
  }
  EXPECT_LT(dx, 6.4e-9 * size);  // O(|L dt|^2 |x|): |L dt| = 8e-5 at most, x within the cell
  EXPECT_TRUE(one.simulation().cell().h.isApprox(stepped.simulation().cell().h, 1e-9));
  EXPECT_NEAR(one.simulation().time(), stepped.simulation().time(), 1e-15 * state.time());
}

// A step in which a pair may touch is stepped, bit for bit as without the option.
TEST(FreeFlight, AStepWithAPossibleCollisionIsStepped) {
  const dem::Simulation& state = contact_free_state();
  dem::Rve stepped = dem::Rve::from_simulation(state, rve_params(false));
  dem::Rve one = dem::Rve::from_simulation(state, rve_params(true));
  const Mat3 l = Mat3::Identity() * -2e2;  // a compression of 0.6 % in volume over 10 us
  const dem::StepReport a = stepped.step(l, 1e-5);
  const dem::StepReport b = one.step(l, 1e-5);
  EXPECT_EQ(b.guards & dem::kGuardFreeFlight, 0u);
  EXPECT_EQ(a.dem_steps, b.dem_steps);
  EXPECT_TRUE(same_bits(stepped.stress(), one.stress()));
  EXPECT_TRUE(same_bits(stepped.simulation().cell().h, one.simulation().cell().h));
  EXPECT_EQ(stepped.simulation().spheres().x, one.simulation().spheres().x);
}

// The option is part of the RVE's state; a state written before it existed steps as it did.
TEST(FreeFlight, TheOptionIsKeptInTheStateAndAbsentMeansStepped) {
  dem::Rve rve(dem_test::reference_packing(), rve_params(true));
  common::StateStore store;
  rve.save(store);
  EXPECT_TRUE(dem::Rve::load(store).params().free_flight);
  common::StateStore old;  // DEM state version 3, without rve/free_flight
  const common::StateStore v3 = dem_test::as_former_version(store, 3);
  for (const auto& [name, field] : v3.fields()) {
    if (name == "rve/free_flight") continue;
    std::visit([&old, &name](const auto& v) { old.write(name, std::span(v)); }, field);
  }
  EXPECT_FALSE(dem::Rve::load(old).params().free_flight);
}

}  // namespace
