// Tests of free_density.hpp: the grid density of a uniform material is its density, at its edges
// too; a loosened point among dense ones reads its neighbourhood's density; only stress-free
// points are limited, to no dilation beyond their neighbourhood; deviatoric rate, spin and the
// plane-strain axis untouched.
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "mpm/free_density.hpp"
#include "mpm/material_points.hpp"
#include "mpm/transfers.hpp"

namespace {

using common::Mat3;
using common::Vec3;

// 4 x 1 x 4 cells of 1 m, a 2 x 2 block of cells filled with 2 x 1 x 2 points per cell.
struct Block {
  mpm::Grid grid{Vec3::Zero(), Vec3::Constant(1.0), common::Vec3i(4, 1, 4)};
  mpm::MaterialPoints points;
  mpm::StencilCache cache;
  std::vector<double> node_m, node_v, rho;
  Block() {
    mpm::fill_box(points, grid, Vec3(1, 0, 1), Vec3(3, 1, 3), common::Vec3i(2, 1, 2), 1500.0, 0);
    points.stress.assign(points.size(), Mat3::Zero());
    points.L.assign(points.size(), Mat3::Zero());
  }
  void density() {
    ASSERT_EQ(mpm::compute_stencils(mpm::ShapeKind::linear, grid, points, cache), -1);
    mpm::grid_density(grid, cache, points, node_m, node_v, rho);
  }
};

TEST(FreeDensity, UniformMaterialReadsItsDensityAtItsEdgesToo) {
  Block b;
  b.density();
  ASSERT_EQ(b.rho.size(), 16U);
  // Every node's ratio is 1500 exactly up to rounding (a ratio of sums of equal densities).
  for (const double r : b.rho) EXPECT_NEAR(r, 1500.0, 1e-9);
}

TEST(FreeDensity, LoosenedPointReadsItsNeighbourhood) {
  Block b;
  // One point loosened to twice its volume (density 750): its neighbourhood is mostly dense.
  b.points.volume[5] *= 2.0;
  b.density();
  EXPECT_GT(b.rho[5], 1200.0);
  EXPECT_LT(b.rho[5], 1500.0);
  // Mass is conserved by construction; the others read slightly less than 1500.
  for (std::size_t p = 0; p < b.rho.size(); ++p) EXPECT_LE(b.rho[p], 1500.0 + 1e-9) << p;
}

TEST(FreeDensity, StressFreePointsDoNotDilateBeyondTheirNeighbourhood) {
  Block b;
  b.points.volume[5] *= 2.0;  // stress-free and looser than its neighbourhood: no dilation
  b.points.volume[6] *= 0.9;  // stress-free and denser: may dilate up to it
  b.density();
  Mat3 l;
  l << 300.0, 0.0, 0.7, 0.0, 0.0, 0.0, -0.2, 0.0, 100.0;  // dilating, plane strain along y
  for (auto& L : b.points.L) L = l;
  b.points.stress[2] = Mat3::Identity() * -1e3;  // carries stress: untouched
  const double dt = 1e-3;
  const std::size_t n = mpm::limit_free_dilation(b.rho, 1, dt, b.points);
  EXPECT_EQ(b.points.L[2], l);
  EXPECT_NEAR(b.points.L[5].trace(), 0.0, 1e-12);
  const double room6 = std::log(b.points.mass[6] / (b.rho[6] * b.points.volume[6])) / dt;
  ASSERT_GT(room6, 0.0);
  ASSERT_LT(room6, l.trace());
  EXPECT_NEAR(b.points.L[6].trace(), room6, 1e-12);
  // The others are at (or within rounding of) their neighbourhood's density, next to points
  // 5 and 6: those looser than it get no dilation.
  EXPECT_GE(n, 2U);
  for (const Mat3& L : {b.points.L[5], b.points.L[6]}) {
    // Deviatoric in-plane part, shear and spin unchanged; nothing through the thickness.
    EXPECT_NEAR(L(0, 0) - L(2, 2), l(0, 0) - l(2, 2), 1e-12);
    EXPECT_EQ(L(0, 2), l(0, 2));
    EXPECT_EQ(L(2, 0), l(2, 0));
    EXPECT_EQ(L(1, 1), 0.0);
  }
  // A compression of its own is kept, however loose the point.
  Block c;
  c.points.volume[5] *= 2.0;
  c.density();
  for (auto& L : c.points.L) L = -l;
  EXPECT_EQ(mpm::limit_free_dilation(c.rho, 1, dt, c.points), 0U);
  EXPECT_EQ(c.points.L[5], -l);
}

TEST(FreeDensity, Names) {
  EXPECT_EQ(mpm::free_density_from_string("grid"), mpm::FreeDensity::grid);
  EXPECT_EQ(mpm::free_density_from_string("point"), mpm::FreeDensity::point);
  EXPECT_EQ(mpm::to_string(mpm::FreeDensity::grid), "grid");
  EXPECT_THROW((void)mpm::free_density_from_string("cell"), common::InputError);
}

}  // namespace
