// Tests of boundary.hpp: face node selection, traction nodal forces (current area, exact sum),
// material extent from F and the domain half-widths.
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "mpm/boundary.hpp"
#include "mpm/transfers.hpp"

namespace {

using common::Vec3;

struct CellSetup {
  mpm::Grid g;
  mpm::MaterialPoints pts;
  mpm::GridFields f;
};

CellSetup single_cell(mpm::ShapeKind kind, int pad) {
  CellSetup s;
  s.g = {Vec3::Constant(-pad), Vec3::Ones(), common::Vec3i::Constant(1 + 2 * pad)};
  mpm::fill_box(s.pts, s.g, Vec3::Zero(), Vec3::Ones(), 2, 1000.0, 0);
  mpm::StencilCache c;
  mpm::PointBins b;
  s.f.resize(s.g);
  EXPECT_EQ(mpm::compute_stencils(kind, s.g, s.pts, c), -1);
  mpm::bin_points(s.g, c, b);
  mpm::activate_nodes(s.g, c, b, s.f);
  return s;
}

TEST(Boundary, FaceConstraintSelectsTheNodePlane) {
  mpm::Grid g{Vec3::Zero(), Vec3(1, 0.5, 2), common::Vec3i(2, 3, 4)};
  const mpm::ResolvedConstraint r =
      mpm::resolve(g, mpm::face_constraint(g, 2, +1, {false, false, true}));
  EXPECT_EQ(r.nodes.size(), 3u * 4u);
  for (auto i : r.nodes) EXPECT_EQ(g.node_ijk(i)[2], 4);
  EXPECT_THROW(mpm::face_constraint(g, 3, 1, {}), common::InputError);
}

TEST(Boundary, SingleCellPressureGivesQuarterFaceForcePerNode) {
  CellSetup s = single_cell(mpm::ShapeKind::linear, 0);
  const mpm::MaterialExtent e = mpm::material_extent(s.pts);
  EXPECT_EQ(e.lo, Vec3::Zero());
  EXPECT_EQ(e.hi, Vec3::Ones());
  const std::vector<std::int64_t> facets = mpm::face_points(s.pts, 0, -1);
  ASSERT_EQ(facets.size(), 4u);  // the 4 points at x = 1/4
  const double A = mpm::apply_traction(s.g, mpm::ShapeKind::linear, {0, -1, 100e3, Vec3::Zero()},
                                       s.pts, facets, s.f);
  EXPECT_EQ(A, 1.0);
  for (auto i : s.f.active) {
    const common::Vec3i ijk = s.g.node_ijk(i);
    // Pressure on the x = 0 face pushes +x: p h^2 / 4 on each of its 4 nodes (to round-off of
    // the Gauss-point weights, 1e-9 N of 2.5e4 N).
    const Vec3 expected = ijk[0] == 0 ? Vec3(25e3, 0, 0) : Vec3::Zero();
    EXPECT_LT((s.f.force[i] - expected).norm(), 1e-9) << ijk.transpose();
  }
}

TEST(Boundary, TractionFollowsTheDeformedAreaNanson) {
  for (auto kind : {mpm::ShapeKind::linear, mpm::ShapeKind::ugimp, mpm::ShapeKind::bspline2}) {
    CellSetup s = single_cell(kind, 1);
    const std::vector<std::int64_t> facets = mpm::face_points(s.pts, 1, +1);
    ASSERT_EQ(facets.size(), 4u);
    // Stretch the points' domains: F = diag(1.02, 0.97, 1.05) without moving them.
    for (auto& F : s.pts.F) F = Vec3(1.02, 0.97, 1.05).asDiagonal();
    const mpm::MaterialExtent e = mpm::material_extent(s.pts);
    EXPECT_NEAR(e.hi[1] - e.lo[1], 0.5 + 0.5 * 0.97, 1e-15);  // 0.5 + 2 * 0.25 * F_yy
    const double A =
        mpm::apply_traction(s.g, kind, {1, +1, 1e5, Vec3(0, 0, 2e3)}, s.pts, facets, s.f);
    // Deformed area of the y face: J / F_yy * A0 = F_xx F_zz (Nanson), exact to round-off.
    EXPECT_NEAR(A, 1.02 * 1.05, 1e-14);
    Vec3 sum = Vec3::Zero();
    for (auto i : s.f.active) sum += s.f.force[i];
    // Pressure on the upper y face pushes -y; the shear traction adds +z; exact to round-off.
    EXPECT_LT((sum - A * Vec3(0, -1e5, 2e3)).norm(), 1e-10 * 1e5) << mpm::to_string(kind);
  }
}

TEST(Boundary, PressureOnARotatedFaceStaysNormalToIt) {
  CellSetup s = single_cell(mpm::ShapeKind::linear, 1);
  const std::vector<std::int64_t> facets = mpm::face_points(s.pts, 0, -1);
  const double c = std::cos(0.2), sn = std::sin(0.2);
  for (auto& F : s.pts.F) F << c, -sn, 0, sn, c, 0, 0, 0, 1;
  const double A = mpm::apply_traction(s.g, mpm::ShapeKind::linear, {0, -1, 1e5, Vec3::Zero()},
                                       s.pts, facets, s.f);
  Vec3 sum = Vec3::Zero();
  for (auto i : s.f.active) sum += s.f.force[i];
  EXPECT_NEAR(A, 1.0, 1e-14);
  // Rotated outward normal R (-e_x); the pressure pushes along R e_x.
  EXPECT_LT((sum - 1e5 * Vec3(c, sn, 0)).norm(), 1e-9);
}

TEST(Boundary, AFacetShearedAwayFromTheMaterialLoadsItsPointsOwnNodes) {
  // The points of one cell, sheared so far (F_xz = 8) that their top facets' Gauss points lie two
  // cells away, among nodes that hold no material (a surface point by a footing's edge): the
  // facet's force goes through the point itself, still summing to -p a exactly (before: exit 3,
  // "touches no node holding material").
  CellSetup s = single_cell(mpm::ShapeKind::linear, 2);
  const std::vector<std::int64_t> facets = mpm::face_points(s.pts, 2, +1);
  ASSERT_EQ(facets.size(), 4u);
  for (auto& F : s.pts.F) F << 1, 0, 8, 0, 1, 0, 0, 0, 1;
  const double A = mpm::apply_traction(s.g, mpm::ShapeKind::linear, {2, +1, 1e5, Vec3::Zero()},
                                       s.pts, facets, s.f);
  Vec3 sum = Vec3::Zero();
  for (auto i : s.f.active) sum += s.f.force[i];
  // Simple shear F = I + 8 e_x e_z keeps the top face's normal and area (Nanson: J = 1,
  // F^-T e_z = e_z); its facets' centres move 8 x 0.25 = 2 cells along x.
  EXPECT_NEAR(A, 1.0, 1e-12);
  EXPECT_LT((sum - Vec3(0, 0, -1e5)).norm(), 1e-9 * 1e5);
  // Every force is on the points' own cell (the only active nodes), none elsewhere.
  for (std::size_t i = 0; i < s.f.force.size(); ++i) {
    if (!s.f.is_active[i]) {
      EXPECT_EQ(s.f.force[i], Vec3::Zero());
    }
  }
}

TEST(Boundary, MirrorConstraintMakesGhostNodesAntisymmetric) {
  mpm::Grid g{Vec3(-1, -1, -1), Vec3::Ones(), common::Vec3i(4, 2, 2)};
  mpm::VelocityConstraint c{
      Vec3::Constant(-10), Vec3(0, 10, 10), {true, false, false}, Vec3::Zero(), {}, 0, 0.0};
  const mpm::ResolvedConstraint r = mpm::resolve(g, c);
  mpm::GridFields f;
  f.resize(g);
  for (std::int64_t i = 0; i < g.num_nodes(); ++i) {
    f.active.push_back(i);
    f.is_active[i] = 1;
    f.velocity[i] = Vec3(g.node_position(i)[0] + 5.0, 1, 2);
    f.acceleration[i] = Vec3(3.0, 0, 0);
  }
  mpm::apply_velocity_constraints(g, {r}, 0.0, f);
  mpm::apply_acceleration_constraints(g, {r}, 0.0, 0.1, f);
  for (std::int64_t i = 0; i < g.num_nodes(); ++i) {
    const common::Vec3i ijk = g.node_ijk(i);
    if (ijk[0] == 0) {  // x = -1: minus its mirror at x = +1 (velocity 6, acceleration 3)
      EXPECT_EQ(f.velocity[i][0], -6.0);
      EXPECT_EQ(f.acceleration[i][0], -3.0);
    } else if (ijk[0] == 1) {  // on the plane
      EXPECT_EQ(f.velocity[i][0], 0.0);
      EXPECT_EQ(f.acceleration[i][0], 0.0);
    } else {
      EXPECT_EQ(f.velocity[i][0], g.node_position(i)[0] + 5.0);
    }
    EXPECT_EQ(f.velocity[i][1], 1.0);
  }
  c.mirror_plane = 0.5;  // not a node plane
  EXPECT_THROW(mpm::resolve(g, c), common::InputError);
}

TEST(Boundary, ExtentFollowsRotation) {
  mpm::MaterialPoints pts;
  pts.add(0, Vec3::Zero(), 1, 1, Vec3(0.5, 0.1, 0.1), 0);
  const double c = std::cos(0.3), sn = std::sin(0.3);
  pts.F[0] << c, -sn, 0, sn, c, 0, 0, 0, 1;
  const mpm::MaterialExtent e = mpm::material_extent(pts);
  EXPECT_NEAR(e.hi[0], c * 0.5 + sn * 0.1, 1e-15);
  EXPECT_NEAR(e.hi[1], sn * 0.5 + c * 0.1, 1e-15);
}

}  // namespace
