// The APIC transfer (mpm/transfers.hpp, Transfer::apic): an affine velocity field goes through
// G2P and P2G exactly, with one point per cell; FLIP/PIC loses it. And the single-cell triaxial
// with ONE point (one RVE) holds its confinement only with APIC (docs/design/mpm.md, "Transfers").
#include <gtest/gtest.h>

#include <cstdio>

#include "mpm/grid_solve.hpp"
#include "mpm/solver.hpp"
#include "mpm/transfers.hpp"
#include "mpm/verification_cases.hpp"

namespace {

using common::Mat3;
using common::Vec3;

// One point per cell on a 4 x 3 x 3 grid, every point with v = v0 + A x and (APIC) C = A; P2G;
// each active node's velocity momentum / mass against v0 + A x_node. Then G2P of those nodal
// velocities gives back v_p and C_p = A.
TEST(Apic, AffineFieldSurvivesTheRoundTripWithOnePointPerCell) {
  const mpm::Grid g{Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(4, 3, 3)};
  Mat3 A;
  A << 0.3, -1.2, 0.5, 0.7, -0.4, 0.1, -0.2, 0.9, 0.25;
  const Vec3 v0(0.1, -0.2, 0.05);
  for (const bool affine : {true, false}) {
    mpm::MaterialPoints pts;
    mpm::fill_box(pts, g, Vec3::Zero(), Vec3(0.4, 0.3, 0.3), 1, 1500.0, 0);
    for (std::size_t p = 0; p < pts.size(); ++p) {
      pts.v[p] = v0 + A * pts.x[p];
      if (affine) pts.C[p] = A;
    }
    mpm::StencilCache cache;
    mpm::PointBins bins;
    mpm::GridFields f;
    f.resize(g);
    ASSERT_EQ(mpm::compute_stencils(mpm::ShapeKind::linear, g, pts, cache), -1);
    mpm::bin_points(g, cache, bins);
    mpm::activate_nodes(g, cache, bins, f);
    mpm::p2g_mass_momentum(g, cache, bins, pts, Vec3::Zero(), f, affine);
    double worst = 0.0;
    for (const std::int64_t i : f.active) {
      const auto k = static_cast<std::size_t>(i);
      f.velocity[k] = f.momentum[k] / f.mass[k];
      worst = std::max(worst, (f.velocity[k] - (v0 + A * g.node_position(i))).norm());
    }
    if (affine) {
      EXPECT_LT(worst, 1e-14) << "APIC P2G of an affine field";
      mpm::MaterialPoints back = pts;
      for (std::size_t p = 0; p < back.size(); ++p) {
        back.v[p].setZero();
        back.C[p].setZero();
      }
      mpm::g2p_update_affine(g, cache, f, 0.0, false, 1e-3, back);
      for (std::size_t p = 0; p < back.size(); ++p) {
        EXPECT_LT((back.v[p] - pts.v[p]).norm(), 1e-14);
        EXPECT_LT((back.C[p] - A).norm(), 1e-13);
      }
    } else {
      // FLIP/PIC: each node averages the constant velocities of the points around it; the
      // field's gradient is lost at the boundary nodes.
      EXPECT_GT(worst, 1e-2) << "FLIP/PIC P2G kept the affine field: the test shows nothing";
    }
  }
}

TEST(Apic, TransferNames) {
  EXPECT_EQ(mpm::transfer_from_string("apic"), mpm::Transfer::apic);
  EXPECT_EQ(mpm::transfer_from_string("flip"), mpm::Transfer::flip);
  EXPECT_EQ(mpm::to_string(mpm::Transfer::apic), "apic");
  EXPECT_THROW((void)mpm::transfer_from_string("pic"), std::exception);
}

// The paper's single cell with ONE point (one RVE) instead of 8, total Lagrangian, to 10 %: with
// FLIP the one point's P2G gives the 8 nodes one velocity, so the cell cannot widen and the
// lateral stress climbs like an oedometer's (measured: 7.5 times p at 10 %); with APIC the affine
// mode is carried and the cell holds 100 kPa as the 8-point cell does (bound: 1 % over the run, the
// platen start's oscillation, as TotalLagrangian.SingleCellHoldsConfinementToThirtyPercent).
TEST(Apic, OnePointCellHoldsConfinementOnlyWithApic) {
  mpm::TriaxialConfig tc;
  tc.move_points = false;
  tc.formulation = mpm::Formulation::total_lagrangian;
  tc.axial_strain = 0.10;
  tc.points_per_cell = 1;
  tc.pin_rigid_modes = true;
  const mpm::TriaxialResult flip = mpm::run_single_cell_triaxial(tc);
  tc.transfer = mpm::Transfer::apic;
  const mpm::TriaxialResult apic = mpm::run_single_cell_triaxial(tc);
  std::printf(
      "one point, 10 %%: lateral error max FLIP %.3e APIC %.3e, end FLIP %.3e APIC %.3e; "
      "axial error APIC %.3e; steps %lld\n",
      flip.lateral_error, apic.lateral_error, flip.lateral_error_end, apic.lateral_error_end,
      apic.axial_error, static_cast<long long>(apic.steps));
  EXPECT_GT(flip.lateral_error_end, 0.5);
  EXPECT_LT(apic.lateral_error, 0.01);
  EXPECT_LT(apic.lateral_error_end, 1e-3);
  EXPECT_LT(apic.axial_error, 0.01);
  EXPECT_NEAR(apic.axial_strain, -0.10, 1e-3);
}

}  // namespace
