// Tests of app::mpm_setup: the example job maps onto the paper's single-cell set-up, and that
// set-up with the linear elastic material keeps the confining pressure (end-to-end mapping check).
#include "app/setup/mpm_setup.hpp"

#include <gtest/gtest.h>

#include "mpm/linear_elastic.hpp"

namespace {
const char* kJob = R"([mpm]
damping = 0.2
end_time = 1.0
dt = 1e-3

[mpm.grid]
origin = [0.0, 0.0, 0.0]
spacing = [1.0, 1.0, 1.0]
cells = [1, 1, 1]

[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]
points_per_cell = 2
density = 1696.0
material = "elastic"
initial_stress = ["-100 kPa", "-100 kPa", "-100 kPa", 0.0, 0.0, 0.0]

[mpm.elastic]
young_modulus = "50 MPa"
poisson_ratio = 0.3

[[mpm.velocity]]
face = "z-"
z = 0.0

[[mpm.velocity]]
face = "z+"
z = "-1 mm/s"

[[mpm.traction]]
face = "x-"
pressure = "100 kPa"
[[mpm.traction]]
face = "x+"
pressure = "100 kPa"
[[mpm.traction]]
face = "y-"
pressure = "100 kPa"
[[mpm.traction]]
face = "y+"
pressure = "100 kPa"
)";
// The frictional-wall, window and name keys of [[mpm.velocity]] map onto the constraint.
TEST(MpmSetup, FrictionalWallWindowAndName) {
  std::string job = kJob;
  job += R"(
[[mpm.velocity]]
min = [0.0, 0.0, 1.0]
max = [1.0, 1.0, 1.0]
z = 0.0
x = "1 mm/s"
friction = 0.4
normal = "z+"
contact = "no_penetration"
from = 0.1
until = "500 ms"
name = "lid"
)";
  const auto setup = app::mpm_setup(app::Job::parse(job, "job.toml"));
  const mpm::VelocityConstraint& lid = setup.constraints.back();
  EXPECT_EQ(lid.name, "lid");
  EXPECT_EQ(setup.constraints[0].name, "velocity_0");
  EXPECT_TRUE(lid.has_wall());
  EXPECT_EQ(lid.wall.axis, 2);
  EXPECT_EQ(lid.wall.side, 1);
  EXPECT_EQ(lid.wall.mu, 0.4);
  EXPECT_EQ(lid.wall.contact, mpm::WallContact::no_penetration);
  EXPECT_EQ(lid.from, 0.1);
  EXPECT_DOUBLE_EQ(lid.until, 0.5);
  EXPECT_DOUBLE_EQ(lid.velocity[0], 1e-3);
  EXPECT_FALSE(setup.constraints[0].has_wall());
  EXPECT_FALSE(setup.constraints[0].has_window());
}

// The choice rows of [mpm] that were written by hand before (mpm/solver_choices.hpp): the thickness
// axis by its name, absent = 3D; move_points a TOML boolean, absent = the member initializer.
TEST(MpmSetup, PlaneStrainAndMovePointsFromTheirRows) {
  std::string job = kJob;
  job.replace(job.find("damping"), 0, "move_points = false\nplane_strain = \"y\"\n");
  const auto setup = app::mpm_setup(app::Job::parse(job, "job.toml"));
  EXPECT_EQ(setup.config.plane_strain_axis, 1);
  EXPECT_FALSE(setup.config.move_points);
  const auto plain = app::mpm_setup(app::Job::parse(kJob, "job.toml"));
  EXPECT_EQ(plain.config.plane_strain_axis, -1);
  EXPECT_EQ(plain.config.move_points, mpm::SolverConfig{}.move_points);
}

}  // namespace

TEST(MpmSetup, PaperSingleCellSetUp) {
  const auto setup = app::mpm_setup(app::Job::parse(kJob, "job.toml"));
  ASSERT_EQ(setup.points.size(), 8u);
  for (const auto& x : setup.points.x) {
    for (int a = 0; a < 3; ++a) EXPECT_TRUE(x[a] == 0.25 || x[a] == 0.75) << x.transpose();
  }
  EXPECT_TRUE(setup.has_elastic);
  EXPECT_FALSE(setup.has_dem);
  EXPECT_DOUBLE_EQ(setup.points.stress[0](0, 0), -1e5);
  EXPECT_EQ(setup.config.flip, 1.0);  // NFLIP
  ASSERT_EQ(setup.constraints.size(), 2u);
  EXPECT_TRUE(setup.constraints[1].fixed[2]);
  EXPECT_DOUBLE_EQ(setup.constraints[1].velocity[2], -1e-3);
  ASSERT_EQ(setup.tractions.size(), 4u);
  EXPECT_EQ(setup.tractions[3].axis, 1);
  EXPECT_EQ(setup.tractions[3].side, 1);
  EXPECT_DOUBLE_EQ(setup.tractions[3].pressure, 1e5);
}

// Elastic triaxial through the mapped set-up: the lateral stress stays at the confining pressure
// (1 %: the tolerance of issue #4's single-cell test) while the axial stress grows.
TEST(MpmSetup, MappedSetUpHoldsTheConfiningPressure) {
  const auto job = app::Job::parse(kJob, "job.toml");
  auto setup = app::mpm_setup(job);
  mpm::LinearElastic elastic(job.number("mpm.elastic.young_modulus"),
                             job.number("mpm.elastic.poisson_ratio"), 1696.0,
                             setup.elastic_initial_stress);
  mpm::Solver solver(setup.config, setup.points, {&elastic});
  for (const auto& c : setup.constraints) solver.add_constraint(c);
  for (const auto& t : setup.tractions) solver.add_traction(t);
  solver.run(300);
  for (std::size_t p = 0; p < solver.points().size(); ++p) {
    const auto& s = solver.points().stress[p];
    EXPECT_NEAR(s(0, 0), -1e5, 1e3) << "point " << p;
    EXPECT_NEAR(s(1, 1), -1e5, 1e3) << "point " << p;
    EXPECT_LT(s(2, 2), -1e5) << "point " << p;  // compressed axially
  }
}

// [[mpm.velocity]] selects a grid face, one node (a box of +/- h/4 around it) or a box of nodes;
// resolved on the grid, each selects exactly the nodes meant.
TEST(MpmSetup, VelocityConstraintsOnFaceNodeAndBox) {
  std::string job = kJob;
  job.replace(job.find("cells = [1, 1, 1]"), 17, "cells = [2, 2, 2]");
  job += R"(
[[mpm.velocity]]
node = [1.0, 0.0, 0.0]
y = 0.0

[[mpm.velocity]]
min = [0.0, 0.0, 2.0]
max = [2.0, 1.0, 2.0]
x = "2 mm/s"
)";
  const auto setup = app::mpm_setup(app::Job::parse(job, "job.toml"));
  ASSERT_EQ(setup.constraints.size(), 4u);
  const mpm::Grid& g = setup.config.grid;
  const mpm::ResolvedConstraint face = mpm::resolve(g, setup.constraints[0]);
  const mpm::ResolvedConstraint node = mpm::resolve(g, setup.constraints[2]);
  const mpm::ResolvedConstraint box = mpm::resolve(g, setup.constraints[3]);
  EXPECT_EQ(face.nodes.size(), 9u);  // the z = 0 plane of a 3 x 3 x 3 node grid
  ASSERT_EQ(node.nodes.size(), 1u);
  EXPECT_EQ(node.nodes[0], g.node_index(1, 0, 0));
  EXPECT_EQ(box.nodes.size(), 6u);  // z = 2, x in {0, 1, 2}, y in {0, 1}
  EXPECT_TRUE(setup.constraints[2].fixed[1] && !setup.constraints[2].fixed[0]);
  EXPECT_DOUBLE_EQ(setup.constraints[3].velocity[0], 2e-3);
}
