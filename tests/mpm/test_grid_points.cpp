// Tests of grid.hpp and material_points.hpp: indexing, validation, regular filling.
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "mpm/grid.hpp"
#include "mpm/material_points.hpp"

namespace {

TEST(Grid, IndexRoundTripAndPositions) {
  mpm::Grid g{common::Vec3(-1, 0, 2), common::Vec3(0.5, 1, 2), common::Vec3i(3, 4, 5)};
  EXPECT_EQ(g.num_nodes(), 4 * 5 * 6);
  for (std::int64_t i = 0; i < g.num_nodes(); ++i) {
    const common::Vec3i ijk = g.node_ijk(i);
    EXPECT_EQ(g.node_index(ijk[0], ijk[1], ijk[2]), i);
  }
  EXPECT_TRUE(g.node_position(g.node_index(3, 4, 5)).isApprox(common::Vec3(0.5, 4, 12)));
  EXPECT_TRUE(g.upper().isApprox(common::Vec3(0.5, 4, 12)));
}

TEST(Grid, RejectsBadSpacingAndCells) {
  mpm::Grid g;
  g.spacing[1] = 0.0;
  EXPECT_THROW(g.validate(), common::InputError);
  g = mpm::Grid{};
  g.cells[2] = 0;
  EXPECT_THROW(g.validate(), common::InputError);
}

TEST(MaterialPoints, FillBoxPlacesPaperPositions) {
  mpm::Grid g{common::Vec3::Zero(), common::Vec3::Ones(), common::Vec3i(1, 1, 1)};
  mpm::MaterialPoints pts;
  EXPECT_EQ(mpm::fill_box(pts, g, common::Vec3::Zero(), common::Vec3::Ones(), 2, 1500.0, 0), 8u);
  double mass = 0.0;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    for (int d = 0; d < 3; ++d) {
      EXPECT_TRUE(pts.x[p][d] == 0.25 || pts.x[p][d] == 0.75);
      EXPECT_EQ(pts.half_width0[p][d], 0.25);
    }
    EXPECT_EQ(pts.volume[p], 0.125);
    EXPECT_EQ(pts.id[p], static_cast<std::int64_t>(p));
    mass += pts.mass[p];
  }
  EXPECT_DOUBLE_EQ(mass, 1500.0);
  EXPECT_NO_THROW(pts.validate());
}

// Per-axis counts: [2, 1, 3] in a 2 x 1 x 1 box of cells 1 x 0.5 x 3 m: positions (k + 1/2) / n
// of each cell per axis, half-widths spacing / (2 n) per axis, the box's mass conserved.
TEST(MaterialPoints, FillBoxPerAxisCounts) {
  mpm::Grid g{common::Vec3::Zero(), common::Vec3(1.0, 0.5, 3.0), common::Vec3i(2, 1, 1)};
  mpm::MaterialPoints pts;
  EXPECT_EQ(mpm::fill_box(pts, g, common::Vec3::Zero(), common::Vec3(2.0, 0.5, 3.0),
                          common::Vec3i(2, 1, 3), 1000.0, 0),
            2u * 2u * 1u * 3u);
  double mass = 0.0;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const double fx = pts.x[p][0] - std::floor(pts.x[p][0]);
    EXPECT_TRUE(fx == 0.25 || fx == 0.75) << pts.x[p][0];
    EXPECT_EQ(pts.x[p][1], 0.25);
    EXPECT_TRUE(pts.x[p][2] == 0.5 || pts.x[p][2] == 1.5 || pts.x[p][2] == 2.5) << pts.x[p][2];
    EXPECT_EQ(pts.half_width0[p], common::Vec3(0.25, 0.25, 0.5));
    EXPECT_DOUBLE_EQ(pts.volume[p], 0.5 * 0.5 * 1.0);
    mass += pts.mass[p];
  }
  EXPECT_DOUBLE_EQ(mass, 1000.0 * 2.0 * 0.5 * 3.0);
  // The scalar form is the per-axis form with equal counts (same points, same order).
  mpm::MaterialPoints a;
  mpm::MaterialPoints b;
  mpm::fill_box(a, g, common::Vec3::Zero(), common::Vec3(2.0, 0.5, 3.0), 2, 1000.0, 0);
  mpm::fill_box(b, g, common::Vec3::Zero(), common::Vec3(2.0, 0.5, 3.0), common::Vec3i(2, 2, 2),
                1000.0, 0);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.half_width0, b.half_width0);
  EXPECT_THROW(mpm::fill_box(pts, g, common::Vec3::Zero(), common::Vec3(2.0, 0.5, 3.0),
                             common::Vec3i(2, 0, 2), 1000.0, 0),
               common::InputError);
}

TEST(MaterialPoints, ValidateRejectsDuplicateIdsAndBadMass) {
  mpm::MaterialPoints pts;
  pts.add(1, common::Vec3::Zero(), 1.0, 1.0, common::Vec3::Constant(0.5), 0);
  pts.add(1, common::Vec3::Zero(), 1.0, 1.0, common::Vec3::Constant(0.5), 0);
  EXPECT_THROW(pts.validate(), common::InputError);
  pts.id[1] = 2;
  pts.mass[1] = 0.0;
  EXPECT_THROW(pts.validate(), common::InputError);
}

}  // namespace
