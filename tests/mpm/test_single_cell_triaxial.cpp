// Verification: the paper's single-cell triaxial set-up (Duverger et al. 2022, section 3) with a
// linear elastic material (verification_cases.hpp, run_single_cell_triaxial).
#include <gtest/gtest.h>

#include <cmath>
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
  std::printf(
      "triaxial linear: lateral error max %.3e end %.3e, axial error %.3e, eps %.4f, "
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
// that grows exponentially; docs/validation/triaxial.md). With the points held at their regular positions
// (SolverConfig::move_points = false) it is stable: lateral stress within 1 % to 3 % axial strain,
// the seed relaxes, the points stay where they were.
TEST(SingleCellTriaxial, ShearSeedWithFixedPointsStaysStable) {
  mpm::TriaxialConfig tc;
  tc.initial_stress_seed(0, 2) = tc.initial_stress_seed(2, 0) = 1.4e3;
  tc.move_points = false;
  const mpm::TriaxialResult r = mpm::run_single_cell_triaxial(tc);
  std::printf(
      "shear seed, fixed points: lateral error max %.3e end %.3e, axial error %.3e, %lld steps\n",
      r.lateral_error, r.lateral_error_end, r.axial_error, static_cast<long long>(r.steps));
  // The first steps see the 1.4 kPa seed as an out-of-balance shear: 1.4 % of p at most.
  EXPECT_LT(r.lateral_error, 0.02);
  EXPECT_LT(r.lateral_error_end, 0.01);
  EXPECT_LT(r.axial_error, 0.01);
  EXPECT_EQ(r.max_displacement, 0.0);
}

// The case of jobs/elastic_triaxial.toml that went unstable (docs/validation/triaxial.md): nu = 0.3 (with
// nu = 0.25 the same set-up stays stable), platen at 1 mm/s, to 1 % axial strain.
mpm::TriaxialConfig unstable_case() {
  mpm::TriaxialConfig tc;
  tc.initial_stress_seed(0, 2) = tc.initial_stress_seed(2, 0) = 1.4e3;
  tc.poisson_ratio = 0.3;
  tc.density = 1696.0;
  tc.inertial_number = 1e-3 / std::sqrt(tc.pressure / tc.density);  // 1 mm/s
  tc.axial_strain = 0.01;
  return tc;
}

// The unstable mode is the rigid motion of the cell in the horizontal plane (translations in x,
// y and the rotation about z), which nothing in the paper's set-up restrains: only z is
// prescribed on the platens, x and y are held by pressures alone. A 3-2-1 support of two bottom
// nodes removes those three motions and nothing else; then the shear seed with MOVING points
// stays stable, with the same bounds as with fixed points.
TEST(SingleCellTriaxial, ShearSeedWithMovingPointsIsStableOnceRigidModesArePinned) {
  mpm::TriaxialConfig tc = unstable_case();
  tc.pin_rigid_modes = true;
  const mpm::TriaxialResult r = mpm::run_single_cell_triaxial(tc);
  std::printf(
      "shear seed, moving points, pinned rigid modes: lateral error max %.3e end %.3e, axial error "
      "%.3e, "
      "max displacement %.3e m, %lld steps\n",
      r.lateral_error, r.lateral_error_end, r.axial_error, r.max_displacement,
      static_cast<long long>(r.steps));
  EXPECT_LT(r.lateral_error, 0.02);
  EXPECT_LT(r.lateral_error_end, 0.01);
  EXPECT_LT(r.axial_error, 0.01);
  // The points follow the homogeneous deformation only: at 1 % axial strain the top points move
  // by 0.75 * 1 % of the cell (measured 6.4 mm; the unstable run moves them by 0.58 m).
  EXPECT_LT(r.max_displacement, 0.01);
}

// The same seed without the pins: unstable (the case above is not stable by accident of the
// seed or of the step): the points rotate away and lateral control is lost.
TEST(SingleCellTriaxial, ShearSeedWithMovingPointsAndFreeRigidModesGoesUnstable) {
  const mpm::TriaxialConfig tc = unstable_case();
  const mpm::TriaxialResult r = mpm::run_single_cell_triaxial(tc);
  std::printf(
      "shear seed, moving points, free rigid modes: lateral error max %.3e, max displacement %.3e "
      "m\n",
      r.lateral_error, r.max_displacement);
  EXPECT_GT(r.lateral_error, 0.05);
}

}  // namespace
