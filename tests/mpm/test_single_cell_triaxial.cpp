// Verification: the paper's single-cell triaxial set-up (Duverger et al. 2022, section 3) with a
// linear elastic material (verification_cases.hpp, run_single_cell_triaxial).
#include <gtest/gtest.h>

#include <cstdio>

#include "mpm/verification_cases.hpp"

namespace {

// Lateral stress within 1 % of p over the whole run (the requirement). What remains is
// understood: the internal force integrates sigma over V / h while the material spans F_xx h,
// so equilibrium gives sigma_xx = -p / F_xx (0.75 % at 3 % axial strain, nu = 0.25), plus the
// small elastic oscillation left by the platen's start (measured max 0.90 %, end 0.57 %).
// Axial stress: -p + E eps_zz with eps_zz = sum dt L_zz; 1 % of E eps (measured 2e-4: the lateral
// deviation enters as 2 nu delta sigma_xx).
TEST(SingleCellTriaxial, LinearPaperSetupHoldsConfinementAndElasticAxialStress) {
  mpm::TriaxialConfig tc;
  const mpm::TriaxialResult r = mpm::run_single_cell_triaxial(tc);
  std::printf("triaxial linear: lateral error max %.3e end %.3e, axial error %.3e, eps %.4f, "
              "mean sigma_lat %.1f Pa, sigma_zz %.1f Pa, %lld steps\n",
              r.lateral_error, r.lateral_error_end, r.axial_error, r.axial_strain, r.mean_lateral,
              r.mean_axial, static_cast<long long>(r.steps));
  EXPECT_LT(r.lateral_error, 0.01);
  EXPECT_LT(r.axial_error, 0.01);
  EXPECT_NEAR(r.axial_strain, -0.03, 1e-4);
}

// The integration-weight error the paper blames: shifting the 8 points by 0.05 h in x (still
// inside the cell) with linear shape functions loses lateral stress control by far more than
// 1 % (measured 270 %); B-splines keep it within 5 % (study_mpm triaxial prints the table).
// CFL 0.2: B-splines on the padded cell have light ghost nodes and are unstable at 0.5.
TEST(SingleCellTriaxial, DisplacedPointsLoseLateralControlWithLinearShapes) {
  mpm::TriaxialConfig tc;
  tc.cfl = 0.2;
  tc.offsets.assign(8, common::Vec3(0.05, 0, 0));
  const mpm::TriaxialResult lin = mpm::run_single_cell_triaxial(tc);
  tc.shape = mpm::ShapeKind::bspline2;
  const mpm::TriaxialResult bsp = mpm::run_single_cell_triaxial(tc);
  std::printf("displaced +0.05 h: lateral error linear %.3e, bspline2 %.3e\n", lin.lateral_error,
              bsp.lateral_error);
  EXPECT_GT(lin.lateral_error, 0.1);
  EXPECT_LT(bsp.lateral_error, lin.lateral_error);
}

// The DEM RVEs carry shear stresses of a few kPa. With such a seed (sigma_xz = 1.4 kPa) and the
// points moving (eq. 10), the paper's set-up goes unstable (the points start a rotation about z
// that grows exponentially; docs/validation.md). With the points held at their regular positions
// (SolverConfig::move_points = false) it is stable: lateral stress within 1 % to 3 % axial strain,
// the seed relaxes, the points stay where they were.
TEST(SingleCellTriaxial, ShearSeedWithFixedPointsStaysStable) {
  mpm::TriaxialConfig tc;
  tc.initial_stress_seed(0, 2) = tc.initial_stress_seed(2, 0) = 1.4e3;
  tc.move_points = false;
  const mpm::TriaxialResult r = mpm::run_single_cell_triaxial(tc);
  std::printf("shear seed, fixed points: lateral error max %.3e end %.3e, axial error %.3e, %lld steps\n",
              r.lateral_error, r.lateral_error_end, r.axial_error, static_cast<long long>(r.steps));
  // The first steps see the 1.4 kPa seed as an out-of-balance shear: 1.4 % of p at most.
  EXPECT_LT(r.lateral_error, 0.02);
  EXPECT_LT(r.lateral_error_end, 0.01);
  EXPECT_LT(r.axial_error, 0.01);
  EXPECT_EQ(r.max_displacement, 0.0);
}

}  // namespace
