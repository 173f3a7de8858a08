// Verification of plane strain (SolverConfig::plane_strain_axis, docs/design/mpm.md "Plane strain"):
// elastic compression against plane-strain Hooke's law, and the L the material is given.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/errors.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Mat3;
using common::Vec3;

/// LinearElastic with an extra constant shear stress sigma_xy (what a DEM RVE returns out of the
/// plane), recording the largest thickness (y) component of the L it is given.
class RecordingMaterial final : public mpm::MaterialModel {
 public:
  RecordingMaterial(double E, double nu, double rho, const Mat3& s0, double shear_xy)
      : inner_(E, nu, rho, s0), shear_xy_(shear_xy) {}
  void update_stress(std::span<const std::int64_t> ids, std::span<const Mat3> L, double dt,
                     std::span<Mat3> stress) override {
    for (const Mat3& l : L) {
      thickness_L =
          std::max({thickness_L, l.row(1).cwiseAbs().maxCoeff(), l.col(1).cwiseAbs().maxCoeff()});
      in_plane_L = std::max(in_plane_L, std::abs(l(2, 2)));
    }
    inner_.update_stress(ids, L, dt, stress);
    for (Mat3& s : stress) s(0, 1) = s(1, 0) = s(0, 1) + shear_xy_;
  }
  double wave_speed() const override { return inner_.wave_speed(); }
  double thickness_L = 0.0;  ///< max |L_y.| or |L_.y| seen [1/s]
  double in_plane_L = 0.0;   ///< max |L_zz| seen [1/s]

 private:
  mpm::LinearElastic inner_;
  double shear_xy_;
};

struct Compression {
  Mat3 stress = Mat3::Zero();  ///< mean point stress at the end [Pa]
  double eps_zz = 0.0;         ///< sum dt mean(L_zz) [-]
  double eps_xx = 0.0;         ///< sum dt mean(L_xx) [-]
  double thickness_L = 0.0;    ///< largest thickness component of L given to the material [1/s]
  double in_plane_L = 0.0;
};

/// One 1 m cell, thickness y, 2 x points_through x 2 points, starting from -p I: bottom held in z,
/// top moving down at 2 mm/s, the x faces under the pressure p, the x = 0 bottom edge held in x
/// (rigid translation). Compressed to eps_zz = -1 %.
Compression compress(mpm::StressUpdate update, int plane_axis, double shear_xy,
                     bool hold_y_faces = false, int points_through = 1) {
  const double E = 50e6, nu = 0.25, rho = 1600.0, p = 100e3;
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  cfg.stress_update = update;
  cfg.damping = 0.2;
  cfg.plane_strain_axis = plane_axis;
  const Mat3 s0 = -p * Mat3::Identity();
  RecordingMaterial material(E, nu, rho, s0, shear_xy);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), common::Vec3i(2, points_through, 2), rho,
                0);
  for (Mat3& s : pts.stress) s = s0;
  mpm::Solver solver(cfg, pts, {&material});
  solver.add_constraint(
      {Vec3::Constant(-10), Vec3(10, 10, 0), {false, false, true}, Vec3::Zero(), {}});
  solver.add_constraint(
      {Vec3(-10, -10, 1), Vec3::Constant(10), {false, false, true}, Vec3(0, 0, -2e-3), {}});
  solver.add_constraint(
      {Vec3::Constant(-0.1), Vec3(0.1, 1.1, 0.1), {true, false, false}, Vec3::Zero(), {}});
  if (hold_y_faces) {
    solver.add_constraint(
        {Vec3::Constant(-10), Vec3::Constant(10), {false, true, false}, Vec3::Zero(), {}});
  }
  for (int side : {-1, 1}) solver.add_traction({0, side, p, Vec3::Zero()});
  Compression c;
  while (c.eps_zz > -0.01) {
    const double dt = solver.next_dt();
    solver.step();
    double lzz = 0.0;
    double lxx = 0.0;
    for (const Mat3& L : solver.points().L) {
      lzz += L(2, 2);
      lxx += L(0, 0);
    }
    const auto n = static_cast<double>(solver.points().size());
    c.eps_zz += dt * lzz / n;
    c.eps_xx += dt * lxx / n;
  }
  for (const Mat3& s : solver.points().stress) {
    c.stress += s / static_cast<double>(solver.points().size());
  }
  c.thickness_L = material.thickness_L;
  c.in_plane_L = material.in_plane_L;
  return c;
}

// Plane-strain Hooke's law from -p I with sigma_xx = -p held and eps_yy = 0:
//   sigma_zz = -p + E / (1 - nu^2) eps_zz,  sigma_yy = -p + nu E / (1 - nu^2) eps_zz,
//   eps_xx = -nu / (1 - nu) eps_zz.
// Tolerances: 1 % of the stress increment E eps / (1 - nu^2) for sigma_zz and sigma_yy, 1 % of p
// for sigma_xx (the pressure acts on the current area while the internal force integrates over
// the cell: sigma_xx = -p / F_xx, 0.08 % at this strain, plus the platen start's elastic
// oscillation, as in the 3D single-cell triaxial), 2 % for the lateral strain ratio.
void check_hooke(mpm::StressUpdate update) {
  const double E = 50e6, nu = 0.25, p = 100e3;
  const Compression c = compress(update, 1, 0.0);
  const double Ep = E / (1 - nu * nu);
  const double dzz = Ep * c.eps_zz;
  std::printf(
      "plane strain %s: eps_zz %.5f eps_xx %.5f (exact %.5f) sigma xx %.1f yy %.1f (exact "
      "%.1f) zz %.1f (exact %.1f) Pa\n",
      update == mpm::StressUpdate::usf ? "usf" : "musl", c.eps_zz, c.eps_xx,
      -nu / (1 - nu) * c.eps_zz, c.stress(0, 0), c.stress(1, 1), -p + nu * dzz, c.stress(2, 2),
      -p + dzz);
  EXPECT_NEAR(c.stress(2, 2), -p + dzz, 0.01 * std::abs(dzz));
  EXPECT_NEAR(c.stress(1, 1), -p + nu * dzz, 0.01 * std::abs(dzz));
  EXPECT_NEAR(c.stress(0, 0), -p, 0.01 * p);
  EXPECT_NEAR(c.eps_xx / c.eps_zz, -nu / (1 - nu), 0.02 * nu / (1 - nu));
  EXPECT_EQ(c.thickness_L, 0.0);
}

TEST(PlaneStrain, ElasticCompressionFollowsPlaneStrainHookeUsf) {
  check_hooke(mpm::StressUpdate::usf);
}

TEST(PlaneStrain, ElasticCompressionFollowsPlaneStrainHookeMusl) {
  check_hooke(mpm::StressUpdate::musl);
}

// An out-of-plane shear stress sigma_xy (1 kPa, as an RVE may return) pushes the two node planes
// of the thickness in opposite x directions. With one point through the thickness the points
// average the two planes and L_xy stays at round-off; with two (2 x 2 x 2 in the one-cell-thick
// grid) holding the y velocity alone (constraints on every node) lets L_xy reach the material;
// plane strain zeroes the thickness row and column of L exactly, whatever the arrangement.
TEST(PlaneStrain, MaterialSeesNoThicknessComponentOfL) {
  const Compression held = compress(mpm::StressUpdate::usf, -1, 1e3, true, 2);
  const Compression plane2 = compress(mpm::StressUpdate::usf, 1, 1e3, false, 2);
  const Compression plane1 = compress(mpm::StressUpdate::musl, 1, 1e3);
  std::printf(
      "sigma_xy 1 kPa, 2 points through: max thickness |L| held velocity only %.3e 1/s, "
      "plane strain %.3e 1/s (in-plane |L_zz| %.3e 1/s)\n",
      held.thickness_L, plane2.thickness_L, plane2.in_plane_L);
  EXPECT_GT(held.thickness_L, 0.01 * held.in_plane_L);
  EXPECT_EQ(plane2.thickness_L, 0.0);
  EXPECT_GT(plane2.in_plane_L, 0.0);
  EXPECT_EQ(plane1.thickness_L, 0.0);
}

TEST(PlaneStrain, GridMustBeOneCellThick) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(2, 2, 2)};
  cfg.plane_strain_axis = 1;
  try {
    cfg.validate();
    FAIL() << "a 2-cell-thick plane-strain grid was accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("exactly 1 cell along y"), std::string::npos) << e.what();
  }
  cfg.plane_strain_axis = 3;
  EXPECT_THROW(cfg.validate(), common::InputError);
  cfg.grid.cells = common::Vec3i(2, 1, 2);
  cfg.plane_strain_axis = 1;
  EXPECT_NO_THROW(cfg.validate());
  cfg.shape = mpm::ShapeKind::ugimp;  // linear through the thickness
  EXPECT_NO_THROW(cfg.validate());
  cfg.shape = mpm::ShapeKind::bspline2;  // its grid basis spans 3 node planes
  EXPECT_THROW(cfg.validate(), common::InputError);
}

// uGIMP: a point whose domain reaches the grid's boundary (in the plane) is refused when the
// solver is built, naming the point and the remedy, not at step 1 as "left the grid"; through the
// thickness its domain fills the one cell, which is allowed (the shape is linear there).
TEST(PlaneStrain, UgimpRefusesADomainOnTheGridBoundary) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3(0.0, 0.0, -1.0), Vec3::Ones(), common::Vec3i(3, 1, 3)};
  cfg.plane_strain_axis = 1;
  cfg.shape = mpm::ShapeKind::ugimp;
  mpm::LinearElastic material(1e6, 0.3, 1000.0);
  mpm::MaterialPoints touching;
  mpm::fill_box(touching, cfg.grid, Vec3(0.0, 0.0, 0.0), Vec3(1.0, 1.0, 1.0),
                common::Vec3i(2, 1, 2), 1000.0, 0);
  try {
    mpm::Solver solver(cfg, touching, {&material});
    FAIL() << "a uGIMP domain on the grid's boundary x = 0 was accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reaches the grid's boundary at x = 0"),
              std::string::npos)
        << e.what();
  }
  mpm::MaterialPoints inside;
  mpm::fill_box(inside, cfg.grid, Vec3(1.0, 0.0, 0.0), Vec3(2.0, 1.0, 1.0),
                common::Vec3i(2, 1, 2), 1000.0, 0);
  EXPECT_NO_THROW(mpm::Solver(cfg, inside, {&material}));
}

}  // namespace

// Plane strain with rough (frictional) platens: the thickness component is held before the walls
// act, so no wall resists slip through the thickness and no reaction has a thickness component
// (before, the rough base of a plane-strain biaxial reported R_y of 4 % of R_z: the out-of-plane
// pressure on the two node planes, resisted by friction). Exactly zero: nothing is left to resist.
TEST(PlaneStrain, RoughWallsReportNoThicknessReaction) {
  const double E = 50e6, nu = 0.25, rho = 1600.0, p = 100e3;
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  cfg.damping = 0.2;
  cfg.plane_strain_axis = 1;
  const Mat3 s0 = -p * Mat3::Identity();
  RecordingMaterial material(E, nu, rho, s0, 0.0);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), common::Vec3i(2, 1, 2), rho, 0);
  for (Mat3& s : pts.stress) s = s0;
  mpm::Solver solver(cfg, pts, {&material});
  mpm::VelocityConstraint base{Vec3::Constant(-10), Vec3(10, 10, 0), {}, Vec3::Zero(), {}};
  base.wall = {2, -1, 10.0, mpm::WallContact::fixed};
  mpm::VelocityConstraint platen{Vec3(-10, -10, 1), Vec3::Constant(10), {}, Vec3(0, 0, -2e-3), {}};
  platen.wall = {2, 1, 10.0, mpm::WallContact::fixed};
  platen.name = "platen";
  solver.add_constraint(base);
  solver.add_constraint(platen);
  for (int side : {-1, 1}) solver.add_traction({0, side, p, Vec3::Zero()});
  for (int k = 0; k < 200; ++k) {
    solver.step();
    for (const Vec3& r : solver.reactions()) ASSERT_EQ(r[1], 0.0) << "step " << k;
  }
  EXPECT_LT(solver.reactions()[1][2], -0.5 * p);  // the platen presses down on the 1 m^2 top
}
