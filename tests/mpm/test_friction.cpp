// Unit tests of the Coulomb wall friction law on one node (src/mpm/friction.hpp) and of its use
// by the constraints (reactions, time window).
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "mpm/boundary.hpp"
#include "mpm/friction.hpp"

namespace {

using common::Vec3;

// A wall below the material (side -1 on z): n = +z. Approaching at -1 m/s with 0.5 m/s slip:
// dv_n = 1, slip reduced by mu dv_n = 0.2 (exact arithmetic on these values: EXPECT_DOUBLE_EQ).
TEST(WallFriction, SlidingNodeLosesMuTimesNormalCorrection) {
  const mpm::WallFriction w{2, -1, 0.2, mpm::WallContact::fixed};
  const mpm::WallCorrection c = mpm::apply_wall_friction(Vec3(0.5, 0, -1), Vec3::Zero(), w);
  EXPECT_TRUE(c.in_contact);
  EXPECT_DOUBLE_EQ(c.velocity[0], 0.3);
  EXPECT_EQ(c.velocity[1], 0.0);
  EXPECT_EQ(c.velocity[2], 0.0);
}

// The reduction is along the slip direction and never reverses it: a large mu sticks.
TEST(WallFriction, RoughWallSticksAndNeverReversesSlip) {
  const mpm::WallFriction w{2, -1, 1e6, mpm::WallContact::fixed};
  const Vec3 v_wall(0.1, -0.2, 0.05);  // a moving wall: relative velocities count
  const mpm::WallCorrection c = mpm::apply_wall_friction(Vec3(0.4, 0.3, -1), v_wall, w);
  EXPECT_EQ(c.velocity, v_wall);
  const mpm::WallFriction smooth{2, -1, 0.0, mpm::WallContact::fixed};
  const mpm::WallCorrection s = mpm::apply_wall_friction(Vec3(0.4, 0.3, -1), v_wall, smooth);
  // Smooth: only the normal component becomes the wall's (1e-15: one rounding of v - v_wall).
  EXPECT_NEAR((s.velocity - Vec3(0.4, 0.3, 0.05)).norm(), 0.0, 1e-15);
  // Direction kept: mu dv_n = 0.5 * 1.05 of a slip of |(0.3, 0.5)| = 0.583.
  const mpm::WallFriction mid{2, -1, 0.5, mpm::WallContact::fixed};
  const mpm::WallCorrection m = mpm::apply_wall_friction(Vec3(0.4, 0.3, -1), v_wall, mid);
  const Vec3 slip0 = Vec3(0.3, 0.5, 0);
  const Vec3 slip1 = m.velocity - v_wall;
  EXPECT_NEAR(slip1.norm(), slip0.norm() - 0.5 * 1.05, 1e-15);
  EXPECT_NEAR(slip1.normalized().dot(slip0.normalized()), 1.0, 1e-15);
}

// no_penetration: a separating node is left alone; fixed: it is held, without friction (the wall
// pulls: no normal compression, no Coulomb resistance).
TEST(WallFriction, SeparationFreeOnlyWithNoPenetration) {
  // Wall on the x+ side of the material: n = -x. A node at -0.3 m/s moves away from it
  // (v . n = 0.3 > 0).
  const mpm::WallFriction np{0, 1, 0.5, mpm::WallContact::no_penetration};
  const Vec3 v(-0.3, 0.2, 0.0);
  const mpm::WallCorrection a = mpm::apply_wall_friction(v, Vec3::Zero(), np);
  EXPECT_FALSE(a.in_contact);
  EXPECT_EQ(a.velocity, v);
  const mpm::WallFriction fx{0, 1, 0.5, mpm::WallContact::fixed};
  const mpm::WallCorrection b = mpm::apply_wall_friction(v, Vec3::Zero(), fx);
  EXPECT_TRUE(b.in_contact);
  EXPECT_EQ(b.velocity, Vec3(0.0, 0.2, 0.0));
  // Approaching the x+ wall (+x): stopped, slip reduced by 0.5 * 0.3.
  const mpm::WallCorrection c = mpm::apply_wall_friction(Vec3(0.3, 0.2, 0), Vec3::Zero(), np);
  EXPECT_TRUE(c.in_contact);
  EXPECT_NEAR(c.velocity[1], 0.05, 1e-16);
  EXPECT_EQ(c.velocity[0], 0.0);
}

mpm::GridFields all_active(const mpm::Grid& g, const Vec3& v, const Vec3& a, double m) {
  mpm::GridFields f;
  f.resize(g);
  for (std::int64_t i = 0; i < g.num_nodes(); ++i) {
    f.active.push_back(i);
    f.is_active[static_cast<std::size_t>(i)] = 1;
    f.mass[static_cast<std::size_t>(i)] = m;
    f.velocity[static_cast<std::size_t>(i)] = v;
    f.acceleration[static_cast<std::size_t>(i)] = a;
  }
  return f;
}

// Reaction = sum m (a_after - a_before) over the constraint's nodes, for plain and wall
// constraints; a node in two constraints counts in each for what that one changed.
TEST(WallFriction, ReactionsAreWhatEachConstraintAdded) {
  const mpm::Grid g{Vec3::Zero(), Vec3::Ones(), common::Vec3i(2, 1, 1)};
  mpm::GridFields f = all_active(g, Vec3(0.1, 0, 0), Vec3(1.0, 0, -4.0), 2.0);
  mpm::VelocityConstraint base = mpm::face_constraint(g, 2, -1, {false, false, false});
  base.wall = {2, -1, 0.25, mpm::WallContact::fixed};
  const mpm::VelocityConstraint left = mpm::face_constraint(g, 0, -1, {true, false, false});
  const std::vector<mpm::ResolvedConstraint> cs{mpm::resolve(g, base), mpm::resolve(g, left)};
  std::vector<Vec3> r;
  mpm::apply_acceleration_constraints(g, cs, 0.0, 0.5, f, &r);
  ASSERT_EQ(r.size(), 2u);
  // Base: 6 nodes of mass 2; trial v = (0.6, 0, -2): dv_n = 2, slip 0.6 -> 0.1, so
  // a = ((0.1, 0, 0) - (0.1, 0, 0)) / 0.5 = 0: reaction 6 * 2 * ((0, 0, 0) - (1, 0, -4)).
  EXPECT_NEAR((r[0] - Vec3(-12.0, 0.0, 48.0)).norm(), 0.0, 1e-12);
  // Left face: 4 nodes, 2 of them on the base already at a_x = 0; the other 2 lose a_x = 1.
  EXPECT_NEAR((r[1] - Vec3(-4.0, 0.0, 0.0)).norm(), 0.0, 1e-12);
}

// A constraint is active for from <= t < until only; outside it leaves the nodes alone.
TEST(WallFriction, TimeWindowGatesTheConstraint) {
  const mpm::Grid g{Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  mpm::VelocityConstraint gate = mpm::face_constraint(g, 0, 1, {true, false, false});
  gate.until = 1.0;
  const std::vector<mpm::ResolvedConstraint> cs{mpm::resolve(g, gate)};
  for (const double t : {0.5, 1.0}) {
    mpm::GridFields f = all_active(g, Vec3(0.3, 0, 0), Vec3(2.0, 0, 0), 1.0);
    std::vector<Vec3> r;
    mpm::apply_velocity_constraints(g, cs, t, f);
    mpm::apply_acceleration_constraints(g, cs, t, 0.1, f, &r);
    const bool active = t < 1.0;
    EXPECT_EQ(f.velocity[1][0], active ? 0.0 : 0.3) << t;
    EXPECT_EQ(f.acceleration[1][0], active ? 0.0 : 2.0) << t;
    EXPECT_EQ(r[0][0], active ? -8.0 : 0.0) << t;
  }
  gate.from = 2.0;  // from after until
  EXPECT_THROW((void)mpm::resolve(g, gate), common::InputError);
}

}  // namespace
