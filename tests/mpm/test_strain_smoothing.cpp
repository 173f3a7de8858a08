// Tests of strain_smoothing.hpp: the smoothed L is the volume-weighted mean per cell, a
// homogeneous field is unchanged, points in different cells are averaged separately, and a
// solver with smoothing gives every point of a cell the same L; the volumetric (B-bar) variant
// shares only the in-plane trace, is its own adjoint, and keeps the points of a cell dilating
// together in a solver.
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "mpm/benchmark.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"
#include "mpm/strain_smoothing.hpp"

namespace {

using common::Mat3;
using common::Vec3;

// Tolerance: the means below are sums of a few terms of order 1: 1e-14 is a few ulps.
constexpr double kTol = 1e-14;

mpm::Grid two_cells() { return {Vec3::Zero(), Vec3::Constant(1.0), common::Vec3i(2, 1, 1)}; }

Mat3 filled(double a) {
  Mat3 m;
  m << a, 2 * a, 3 * a, -a, 0.5 * a, 0.0, 0.25 * a, a, -2 * a;
  return m;
}

TEST(StrainSmoothing, VolumeWeightedMeanPerCell) {
  const mpm::Grid g = two_cells();
  // Three points in cell 0 (x < 1), two in cell 1.
  std::vector<Vec3> x = {Vec3(0.2, 0.5, 0.5), Vec3(1.3, 0.5, 0.5), Vec3(0.7, 0.1, 0.9),
                         Vec3(1.9, 0.9, 0.1), Vec3(0.5, 0.5, 0.5)};
  std::vector<double> vol = {1.0, 2.0, 3.0, 0.5, 4.0};
  std::vector<Mat3> L = {filled(1.0), filled(10.0), filled(-2.0), filled(4.0), filled(0.5)};
  const Mat3 mean0 = (1.0 * filled(1.0) + 3.0 * filled(-2.0) + 4.0 * filled(0.5)) / 8.0;
  const Mat3 mean1 = (2.0 * filled(10.0) + 0.5 * filled(4.0)) / 2.5;
  std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
  mpm::average_per_cell(g, x, vol, L, scratch);
  for (const std::size_t p : {0U, 2U, 4U}) EXPECT_LT((L[p] - mean0).norm(), kTol) << p;
  for (const std::size_t p : {1U, 3U}) EXPECT_LT((L[p] - mean1).norm(), kTol) << p;
  // The volume-weighted sum over each cell (the cell's deformation rate) is conserved.
  EXPECT_LT((vol[0] * L[0] + vol[2] * L[2] + vol[4] * L[4] -
             (1.0 * filled(1.0) + 3.0 * filled(-2.0) + 4.0 * filled(0.5)))
                .norm(),
            1e-13);
}

TEST(StrainSmoothing, HomogeneousFieldUnchanged) {
  const mpm::Grid g = two_cells();
  std::vector<Vec3> x = {Vec3(0.1, 0.2, 0.3), Vec3(0.9, 0.8, 0.7), Vec3(1.5, 0.5, 0.5),
                         Vec3(1.2, 0.3, 0.6)};
  std::vector<double> vol = {0.3, 1.7, 2.0, 0.01};
  std::vector<Mat3> L(4, filled(0.3));
  const std::vector<Mat3> before = L;
  std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
  mpm::average_per_cell(g, x, vol, L, scratch);
  for (std::size_t p = 0; p < L.size(); ++p) EXPECT_LT((L[p] - before[p]).norm(), kTol) << p;
}

TEST(StrainSmoothing, CellOfAPoint) {
  const mpm::Grid g{Vec3(-1, 0, 0), Vec3(0.5, 1.0, 2.0), common::Vec3i(4, 2, 3)};
  EXPECT_EQ(mpm::cell_of(g, Vec3(-0.9, 0.1, 0.1)), 0);
  EXPECT_EQ(mpm::cell_of(g, Vec3(-0.5, 0.1, 0.1)), 1);  // on a face: the cell above
  EXPECT_EQ(mpm::cell_of(g, Vec3(1.0, 2.0, 6.0)), 3 + 4 * (1 + 2 * 2));  // upper corner: last
  EXPECT_EQ(mpm::cell_of(g, Vec3(0.2, 1.5, 2.5)), 2 + 4 * (1 + 2 * 1));
}

TEST(StrainSmoothing, NamesAndErrors) {
  EXPECT_EQ(mpm::strain_smoothing_from_string("cell"), mpm::StrainSmoothing::cell);
  EXPECT_EQ(mpm::strain_smoothing_from_string("none"), mpm::StrainSmoothing::none);
  EXPECT_EQ(mpm::to_string(mpm::StrainSmoothing::cell), "cell");
  EXPECT_EQ(mpm::strain_smoothing_from_string("volumetric"), mpm::StrainSmoothing::volumetric);
  EXPECT_THROW((void)mpm::strain_smoothing_from_string("node"), common::InputError);
}

// A solver step with smoothing: every point of a cell sees the same L, and it is the
// volume-weighted mean of the L the unsmoothed solver computes from the same state.
void check_solver(mpm::StressUpdate update) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.25), common::Vec3i(4, 4, 6)};
  cfg.gravity = Vec3(0, 0, -9.81);
  cfg.stress_update = update;
  cfg.strain_smoothing = mpm::StrainSmoothing::cell;
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3(0.25, 0.25, 0.25), Vec3(0.75, 0.75, 1.25), 2, 1800.0, 0);
  mpm::LinearElastic mat(1e6, 0.3, 1800.0);
  mpm::Solver s(cfg, pts, {&mat});
  s.add_constraint(mpm::face_constraint(cfg.grid, 2, -1, {true, true, true}));
  s.run(5);
  const mpm::MaterialPoints& p = s.points();
  std::size_t nonzero = 0;
  for (std::size_t a = 0; a < p.size(); ++a) {
    for (std::size_t b = 0; b < p.size(); ++b) {
      if (mpm::cell_of(cfg.grid, p.x[a]) == mpm::cell_of(cfg.grid, p.x[b])) {
        EXPECT_EQ(p.L[a], p.L[b]) << a << " " << b;
      }
    }
    if (p.L[a].norm() > 0.0) ++nonzero;
  }
  EXPECT_GT(nonzero, 0U);  // the column is loaded by its weight: L is not trivially zero
}

TEST(StrainSmoothing, SolverUsfSameLPerCell) { check_solver(mpm::StressUpdate::usf); }
TEST(StrainSmoothing, SolverMuslSameLPerCell) { check_solver(mpm::StressUpdate::musl); }

// Hourglass control: 8 points of one cell with two stresses in a yz pattern (it drives the yz
// hourglass mode of v_x: sigma_xx varying with y z, not with x). The
// forces of the cell's mean stress make the first step's velocity field affine: its hourglass
// parts (the sums of v_p weighted by the xy, yz, zx and xyz sign patterns of the points) vanish.
// Without smoothing the stress differences drive them.
double hourglass_velocity(mpm::StrainSmoothing smoothing) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  cfg.strain_smoothing = smoothing;
  cfg.dt = 1e-5;
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), 2, 1800.0, 0);
  const Vec3 c(0.5, 0.5, 0.5);
  auto sign = [&](std::size_t p, int d) { return pts.x[p][d] > c[d] ? 1.0 : -1.0; };
  for (std::size_t p = 0; p < pts.size(); ++p)
    pts.material[p] = sign(p, 1) * sign(p, 2) > 0 ? 1 : 0;
  mpm::LinearElastic soft(1e6, 0.3, 1800.0, -1e5 * Mat3::Identity());
  mpm::LinearElastic hard(1e6, 0.3, 1800.0, -2e5 * Mat3::Identity());
  mpm::Solver s(cfg, pts, {&soft, &hard});
  s.step();
  const mpm::MaterialPoints& q = s.points();
  double worst = 0.0;
  double scale = 0.0;
  const int pairs[4][3] = {{0, 1, -1}, {1, 2, -1}, {2, 0, -1}, {0, 1, 2}};
  for (const auto& pattern : pairs) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t p = 0; p < q.size(); ++p) {
      double w = sign(p, pattern[0]) * sign(p, pattern[1]);
      if (pattern[2] >= 0) w *= sign(p, pattern[2]);
      sum += w * q.v[p];
    }
    worst = std::max(worst, sum.norm());
  }
  for (std::size_t p = 0; p < q.size(); ++p) scale = std::max(scale, q.v[p].norm());
  EXPECT_GT(scale, 0.0);  // the free cube does move
  return worst / scale;
}

TEST(StrainSmoothing, MeanStressForcesDriveNoHourglassMode) {
  // 1e-12: the hourglass sums of an affine field cancel to rounding of velocities of order 1.
  EXPECT_LT(hourglass_velocity(mpm::StrainSmoothing::cell), 1e-12);
  EXPECT_GT(hourglass_velocity(mpm::StrainSmoothing::none), 1e-3);
}

// The volumetric variant: each point keeps its own L but the trace over the in-plane axes, which
// becomes the cell's volume-weighted mean, spread equally over those axes; the thickness axis's
// entries and every off-diagonal entry are the point's own.
TEST(StrainSmoothing, VolumetricSharesOnlyTheTrace) {
  const mpm::Grid g = two_cells();
  std::vector<Vec3> x = {Vec3(0.2, 0.5, 0.5), Vec3(1.3, 0.5, 0.5), Vec3(0.7, 0.1, 0.9),
                         Vec3(0.5, 0.5, 0.5)};
  std::vector<double> vol = {1.0, 2.0, 3.0, 4.0};
  const std::vector<Mat3> before = {filled(1.0), filled(10.0), filled(-2.0), filled(0.5)};
  for (const int axis : {-1, 1}) {
    std::vector<Mat3> L = before;
    std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
    mpm::average_trace_per_cell(g, x, vol, axis, L, scratch);
    auto trace = [&](const Mat3& m) { return m.trace() - (axis >= 0 ? m(axis, axis) : 0.0); };
    const double mean0 =
        (1.0 * trace(before[0]) + 3.0 * trace(before[2]) + 4.0 * trace(before[3])) / 8.0;
    for (const std::size_t p : {0U, 2U, 3U}) {
      EXPECT_NEAR(trace(L[p]), mean0, kTol) << p << " axis " << axis;
      const Mat3 change = L[p] - before[p];
      const double shift = (mean0 - trace(before[p])) / (axis >= 0 ? 2.0 : 3.0);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          const double want = (a == b && a != axis) ? shift : 0.0;
          EXPECT_NEAR(change(a, b), want, kTol) << p << " (" << a << ", " << b << ")";
        }
      }
    }
    // A lone point in its cell is unchanged.
    EXPECT_LT((L[1] - before[1]).norm(), kTol);
  }
}

// Its own adjoint for sum_p V_p A_p : B_p (cells of several points): the forces of the averaged
// stress have the power of the material's stress on the averaged L.
TEST(StrainSmoothing, VolumetricIsItsOwnAdjoint) {
  const mpm::Grid g = two_cells();
  std::vector<Vec3> x = {Vec3(0.2, 0.5, 0.5), Vec3(1.3, 0.5, 0.5), Vec3(0.7, 0.1, 0.9),
                         Vec3(1.9, 0.9, 0.1), Vec3(0.5, 0.5, 0.5)};
  std::vector<double> vol = {1.0, 2.0, 3.0, 0.5, 4.0};
  std::vector<Mat3> A = {filled(1.0), filled(10.0), filled(-2.0), filled(4.0), filled(0.5)};
  std::vector<Mat3> B = {filled(-3.0).transpose(), filled(0.1), filled(7.0).transpose(),
                         filled(-1.0), filled(2.0).transpose()};
  auto power = [&](const std::vector<Mat3>& a, const std::vector<Mat3>& b) {
    double s = 0.0;
    for (std::size_t p = 0; p < a.size(); ++p) s += vol[p] * (a[p].array() * b[p].array()).sum();
    return s;
  };
  std::vector<std::pair<std::int64_t, std::int64_t>> scratch;
  for (const int axis : {-1, 1}) {
    std::vector<Mat3> Aa = A;
    std::vector<Mat3> Ba = B;
    mpm::average_trace_per_cell(g, x, vol, axis, Aa, scratch);
    mpm::average_trace_per_cell(g, x, vol, axis, Ba, scratch);
    // Terms of order 100-1000: 1e-11 is a few ulps of their sum.
    EXPECT_NEAR(power(Aa, B), power(A, Ba), 1e-11) << axis;
    EXPECT_GT(std::abs(power(Aa, B) - power(A, B)), 1.0) << axis;  // the operator does act
  }
}

// In a solver (plane strain through y, a column of 2 x 2 points per cell under its weight, two
// materials in a pattern that makes the points of a cell strain differently): with "volumetric"
// the points of a cell have one volumetric rate (the trace of L, over x and z) and differ in
// their shear rates; without smoothing their volumetric rates differ.
double trace_spread(mpm::StrainSmoothing smoothing, double* shear_spread, double* scale) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.25), common::Vec3i(4, 1, 6)};
  cfg.gravity = Vec3(0, 0, -9.81);
  cfg.plane_strain_axis = 1;
  cfg.strain_smoothing = smoothing;
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3(0.25, 0.0, 0.0), Vec3(0.75, 0.25, 1.0), 2, 1800.0, 0);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const double u = pts.x[p][0] / 0.25;
    const double w = pts.x[p][2] / 0.25;
    pts.material[p] = (u - std::floor(u) > 0.5) == (w - std::floor(w) > 0.5) ? 1 : 0;
  }
  mpm::LinearElastic soft(1e5, 0.3, 1800.0);
  mpm::LinearElastic hard(1e6, 0.3, 1800.0);
  mpm::Solver s(cfg, pts, {&soft, &hard});
  s.add_constraint(mpm::face_constraint(cfg.grid, 2, -1, {true, true, true}));
  s.run(20);
  const mpm::MaterialPoints& q = s.points();
  double spread = 0.0;
  *shear_spread = 0.0;
  *scale = 0.0;
  for (std::size_t a = 0; a < q.size(); ++a) {
    *scale = std::max(*scale, q.L[a].norm());
    for (std::size_t b = 0; b < q.size(); ++b) {
      if (mpm::cell_of(cfg.grid, q.x[a]) != mpm::cell_of(cfg.grid, q.x[b])) continue;
      spread = std::max(spread, std::abs(q.L[a].trace() - q.L[b].trace()));
      *shear_spread = std::max(*shear_spread, std::abs(q.L[a](0, 2) - q.L[b](0, 2)));
    }
  }
  return spread;
}

TEST(StrainSmoothing, SolverVolumetricPointsOfACellDilateTogether) {
  double shear_none = 0.0;
  double shear_volumetric = 0.0;
  double scale = 0.0;
  const double none = trace_spread(mpm::StrainSmoothing::none, &shear_none, &scale);
  EXPECT_GT(none, 1e-3 * scale);  // without smoothing the points of a cell dilate differently
  const double volumetric =
      trace_spread(mpm::StrainSmoothing::volumetric, &shear_volumetric, &scale);
  EXPECT_GT(scale, 0.0);
  // With it the traces agree to the rounding of a mean of four terms and a shift (1e-14 of L).
  EXPECT_LT(volumetric, 1e-14 * scale);
  EXPECT_GT(shear_volumetric, 1e-3 * scale);  // each keeps its own shear rate
}

}  // namespace
