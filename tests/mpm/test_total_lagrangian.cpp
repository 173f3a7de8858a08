// The total Lagrangian formulation (mpm/formulation.hpp): with fixed points the grid is the
// reference configuration, and the paper's single cell then holds its confining pressure at any
// strain (the updated Lagrangian one gives sigma_xx = -p / F_xx).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/types.hpp"
#include "mpm/formulation.hpp"
#include "mpm/verification_cases.hpp"

namespace {

using common::Mat3;

TEST(Formulation, Names) {
  EXPECT_EQ(mpm::formulation_from_string("total_lagrangian"), mpm::Formulation::total_lagrangian);
  EXPECT_EQ(mpm::formulation_from_string("updated_lagrangian"),
            mpm::Formulation::updated_lagrangian);
  EXPECT_EQ(mpm::to_string(mpm::Formulation::total_lagrangian), "total_lagrangian");
  EXPECT_THROW((void)mpm::formulation_from_string("eulerian"), std::exception);
}

// Fdot F^-1 and sigma F^-T on a general F (shear and stretch): checked against F F^-1 = I and
// the identity (sigma F^-T) F^T = sigma, to round-off.
TEST(Formulation, MapsGradientsThroughF) {
  Mat3 F;
  F << 1.2, 0.1, 0.0, 0.05, 0.9, 0.02, 0.0, -0.03, 0.8;
  std::vector<Mat3> Fs{F};
  std::vector<Mat3> L{F};  // Fdot = F gives L = I
  mpm::to_spatial_gradient(Fs, L);
  EXPECT_LT((L[0] - Mat3::Identity()).norm(), 1e-14);
  Mat3 s;
  s << -1e5, 2e3, 0, 2e3, -2e5, 1e3, 0, 1e3, -1.5e5;
  std::vector<Mat3> out;
  mpm::stress_for_reference_gradient(Fs, {s}, out);
  EXPECT_LT((out[0] * F.transpose() - s).norm(), 1e-9 * s.norm());
}

// The paper's single cell (elastic, E = 50 MPa, nu = 0.25, p = 100 kPa, fixed points) to 30 %
// axial strain. Updated Lagrangian: sigma_xx = -p / F_xx, F_xx = 1.075 here, so the lateral
// stress ends 7 % low (measured 7.06 %; the assertion only says "more than 5 %"). Total
// Lagrangian: equilibrium of the reference cell with the Nanson force gives sigma_xx = -p
// exactly; what is left is the platen start's elastic oscillation (0.9 % in the 3 % test of
// test_single_cell_triaxial.cpp; measured here 0.26 % at most, 5e-6 at the end): 1 % over the
// run, 1e-4 at the end (the oscillation damped out). At I = 1e-3 instead of the paper's 2.5e-4
// the end error is 0.7 %: the inertia of the widening cell. Axial: -p + E eps (eps = sum dt L_zz,
// the logarithmic strain of a hypoelastic law), 1 % of E eps (measured 2e-8).
TEST(TotalLagrangian, SingleCellHoldsConfinementToThirtyPercent) {
  mpm::TriaxialConfig tc;
  tc.move_points = false;
  tc.axial_strain = 0.30;
  const mpm::TriaxialResult ul = mpm::run_single_cell_triaxial(tc);
  tc.formulation = mpm::Formulation::total_lagrangian;
  const mpm::TriaxialResult tl = mpm::run_single_cell_triaxial(tc);
  std::printf(
      "30 %% axial strain: lateral error end UL %.3e TL %.3e, max TL %.3e; axial error UL %.3e "
      "TL %.3e; mean lateral UL %.1f TL %.1f Pa; steps UL %lld TL %lld\n",
      ul.lateral_error_end, tl.lateral_error_end, tl.lateral_error, ul.axial_error, tl.axial_error,
      ul.mean_lateral, tl.mean_lateral, static_cast<long long>(ul.steps),
      static_cast<long long>(tl.steps));
  EXPECT_GT(ul.lateral_error_end, 0.05);
  EXPECT_LT(tl.lateral_error, 0.01);
  EXPECT_LT(tl.lateral_error_end, 1e-4);
  EXPECT_LT(tl.axial_error, 0.01);
  EXPECT_NEAR(tl.axial_strain, -0.30, 1e-3);
  EXPECT_EQ(tl.max_displacement, 0.0);  // fixed points
}

}  // namespace
