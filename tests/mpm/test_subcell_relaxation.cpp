// Tests of subcell_relaxation.hpp: the added strain rates keep each cell's deformation rate,
// extend a point that carries more than its cell's mean and compress one that carries less, have
// a stress power that is minus the stress spread over rho c^2 tau, leave the thickness axis and
// a uniform or lone point alone; in a solver, a stress pattern inside a cell relaxes with it and
// persists without it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mpm/benchmark.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"
#include "mpm/strain_smoothing.hpp"
#include "mpm/subcell_relaxation.hpp"

namespace {

using common::Mat3;
using common::Vec3;

mpm::Grid two_cells() { return {Vec3::Zero(), Vec3::Constant(1.0), common::Vec3i(2, 1, 1)}; }

Mat3 sym(double a, double b, double c, double d, double e, double f) {
  Mat3 m;
  m << a, d, e, d, b, f, e, f, c;
  return m;
}

struct Cells {
  std::vector<Vec3> x = {Vec3(0.2, 0.5, 0.5), Vec3(1.3, 0.5, 0.5), Vec3(0.7, 0.1, 0.9),
                         Vec3(0.5, 0.5, 0.5)};
  std::vector<double> mass = {2000.0, 1000.0, 5000.0, 7000.0};
  std::vector<double> vol = {1.0, 2.0, 3.0, 4.0};
  // Cell 0 holds points 0, 2, 3 (point 0 carries the most compression); point 1 is alone.
  std::vector<Mat3> stress = {sym(-300, -100, -500, 10, 0, -20), sym(-50, -50, -50, 0, 0, 0),
                              sym(0, 0, 0, 0, 0, 0), sym(-60, -30, -90, 5, 1, 2)};
};

constexpr double kC = 20.0;    // wave speed [m/s]
constexpr double kTau = 0.01;  // relaxation time [s]

TEST(SubcellRelaxation, KeepsTheCellsRateAndTurnsTheRightWay) {
  const Cells c;
  for (const int axis : {-1, 1}) {
    std::vector<Mat3> L(4, Mat3::Zero());
    std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
    mpm::relax_subcell_stress(two_cells(), c.x, c.mass, c.vol, c.stress, axis, kC, kTau, L,
                              scratch);
    // Rates of order 0.1 times volumes of order 1: 1e-15 is rounding.
    EXPECT_LT((c.vol[0] * L[0] + c.vol[2] * L[2] + c.vol[3] * L[3]).norm(), 1e-15) << axis;
    EXPECT_EQ(L[1], Mat3::Zero());  // alone in its cell
    // rho = 14000 kg / 8 m^3; the mean stress of cell 0; the rate of point 0, component by
    // component (the thickness axis's row and column excepted).
    const double rho = 14000.0 / 8.0;
    const Mat3 mean = (1.0 * c.stress[0] + 3.0 * c.stress[2] + 4.0 * c.stress[3]) / 8.0;
    const Mat3 want = -(c.stress[0] - mean) / (rho * kC * kC * kTau);
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const double w = (a == axis || b == axis) ? 0.0 : want(a, b);
        EXPECT_NEAR(L[0](a, b), w, 1e-15) << a << b;  // rates of order 0.1: rounding
      }
    }
    EXPECT_GT(L[0](2, 2), 0.0);  // the most compressed point extends along z
    EXPECT_LT(L[2](2, 2), 0.0);  // the stress-free point is compressed
  }
}

TEST(SubcellRelaxation, StressPowerIsMinusTheSpread) {
  const Cells c;
  std::vector<Mat3> L(4, Mat3::Zero());
  std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
  mpm::relax_subcell_stress(two_cells(), c.x, c.mass, c.vol, c.stress, -1, kC, kTau, L, scratch);
  double power = 0.0;
  for (std::size_t p = 0; p < 4; ++p)
    power += c.vol[p] * (c.stress[p].array() * L[p].array()).sum();
  const Mat3 mean = (1.0 * c.stress[0] + 3.0 * c.stress[2] + 4.0 * c.stress[3]) / 8.0;
  double spread = 0.0;
  for (const std::size_t p : {0U, 2U, 3U}) spread += c.vol[p] * (c.stress[p] - mean).squaredNorm();
  const double want = -spread / ((14000.0 / 8.0) * kC * kC * kTau);
  EXPECT_LT(power, 0.0);
  EXPECT_NEAR(power, want, 1e-12 * std::abs(want));
}

TEST(SubcellRelaxation, UniformStressIsLeftAlone) {
  Cells c;
  for (Mat3& s : c.stress) s = sym(-10, -20, -30, 1, 2, 3);
  std::vector<Mat3> L(4, Mat3::Identity());
  std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
  mpm::relax_subcell_stress(two_cells(), c.x, c.mass, c.vol, c.stress, -1, kC, kTau, L, scratch);
  // The cell mean of equal stresses is that stress to rounding (1e-14 of 30 Pa, over rho c^2 tau).
  for (const Mat3& l : L) EXPECT_LT((l - Mat3::Identity()).norm(), 1e-15);
}

// One cell of 2 x 2 x 2 points of one elastic material whose initial stresses differ (a yz
// pattern, as in the hourglass test of test_strain_smoothing.cpp): without relaxation the
// pattern stays; with subcell_relaxation = 2 the points' pressures approach each other.
double pressure_spread(double relaxation) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  cfg.subcell_relaxation = relaxation;
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), 2, 1800.0, 0);
  const Vec3 mid(0.5, 0.5, 0.5);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    pts.material[p] = (pts.x[p][1] > mid[1]) == (pts.x[p][2] > mid[2]) ? 1 : 0;
  }
  mpm::LinearElastic soft(1e6, 0.3, 1800.0, -1e5 * Mat3::Identity());
  mpm::LinearElastic hard(1e6, 0.3, 1800.0, -2e5 * Mat3::Identity());
  mpm::Solver s(cfg, pts, {&soft, &hard});
  s.run(40);
  double lo = 1e300;
  double hi = -1e300;
  for (const Mat3& sigma : s.points().stress) {
    lo = std::min(lo, -sigma.trace() / 3.0);
    hi = std::max(hi, -sigma.trace() / 3.0);
  }
  return hi - lo;
}

TEST(SubcellRelaxation, SolverRelaxesAPatternThatPersistsWithout) {
  const double without = pressure_spread(0.0);
  const double with = pressure_spread(2.0);
  EXPECT_GT(without, 4e4);  // of the initial 1e5 Pa difference about half stays (52 kPa)
  EXPECT_LT(with, 0.01 * without);  // 25 Pa
}

TEST(SubcellRelaxation, NeedsAWaveSpeedAndATime) {
  const Cells c;
  std::vector<Mat3> L(4, Mat3::Zero());
  std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
  EXPECT_THROW(mpm::relax_subcell_stress(two_cells(), c.x, c.mass, c.vol, c.stress, -1, 0.0, kTau,
                                         L, scratch),
               common::NumericalError);
  EXPECT_THROW(
      mpm::relax_subcell_stress(two_cells(), c.x, c.mass, c.vol, c.stress, -1, kC, 0.0, L, scratch),
      common::NumericalError);
}

}  // namespace
