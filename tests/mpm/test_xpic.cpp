// Tests of xpic.hpp, the XPIC(m) update of Hammerquist & Nairn (2017), against its defining
// property: on the points it is (I - (I - P)^m) v with P the PIC round trip, so
//  - a rigid translation goes through unchanged (the coefficients sum to 1);
//  - the sub-cell noise in P's null space is removed as by PIC (a mode with P v = 0);
//  - a smooth mode that PIC damps by a relative loss e is damped by about e^m;
// and the prescribed components of V are kept, the same bits on any number of threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "mpm/grid_solve.hpp"
#include "mpm/parallel.hpp"
#include "mpm/transfers.hpp"
#include "mpm/xpic.hpp"

namespace {

using common::Vec3;

/// A bar of 2 x 2 x 2 points per cell along x (cells x 1 x 1 cells of 0.1 m), on the grid.
struct Bar {
  mpm::Grid g;
  mpm::MaterialPoints pts;
  mpm::StencilCache cache;
  mpm::PointBins bins;
  mpm::GridFields f;
  explicit Bar(int cells) : g{Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(cells, 1, 1)} {
    mpm::fill_box(pts, g, Vec3::Zero(), g.upper(), 2, 1000.0, 0);
    EXPECT_EQ(mpm::compute_stencils(mpm::ShapeKind::linear, g, pts, cache), -1);
  }
  /// P2G of the points' velocities: the grid's V (no constraint, no gravity).
  void project() {
    f.resize(g);
    EXPECT_EQ(mpm::compute_stencils(mpm::ShapeKind::linear, g, pts, cache), -1);  // moved points
    mpm::bin_points(g, cache, bins);
    mpm::activate_nodes(g, cache, bins, f);
    mpm::p2g_mass_momentum(g, cache, bins, pts, Vec3::Zero(), f);
    mpm::compute_nodal_velocity(1e-12, f);
    for (const auto i : f.active) f.acceleration[static_cast<std::size_t>(i)].setZero();
  }
  /// The points' velocities after a full-PIC-share update whose grid velocity is XPIC(m)'s V*
  /// (m = 1: V itself, PIC).
  std::vector<Vec3> update(int order) {
    mpm::MaterialPoints copy = pts;
    std::vector<Vec3> v_star;
    mpm::XpicScratch scratch;
    mpm::xpic_velocity(g, cache, bins, copy, f, 1e-12, order, scratch, v_star);
    mpm::g2p_update(g, cache, f, 1.0, false, 1e-3, copy, false, false, &v_star);
    return copy.v;
  }
};

}  // namespace

// Order 1 is PIC: V* = V, bit for bit.
TEST(Xpic, OrderOneIsPic) {
  Bar bar(6);
  for (std::size_t p = 0; p < bar.pts.size(); ++p) bar.pts.v[p] = Vec3(std::sin(7.0 * p), 0, 0);
  bar.project();
  std::vector<Vec3> v_star;
  mpm::XpicScratch scratch;
  mpm::xpic_velocity(bar.g, bar.cache, bar.bins, bar.pts, bar.f, 1e-12, 1, scratch, v_star);
  for (const auto i : bar.f.active) {
    EXPECT_EQ(v_star[static_cast<std::size_t>(i)], bar.f.velocity[static_cast<std::size_t>(i)]);
  }
}

// A rigid translation, also at the bar's ends (partition of unity), for every order: to
// round-off (terms of size C(m, k) <= 70 summed to 1, relative 1e-13).
TEST(Xpic, KeepsARigidTranslation) {
  Bar bar(5);
  const Vec3 u(0.3, -1.2, 2.0);
  for (auto& v : bar.pts.v) v = u;
  bar.project();
  for (int m = 2; m <= 8; ++m) {
    for (const Vec3& v : bar.update(m)) EXPECT_LT((v - u).norm(), 1e-13 * u.norm()) << "m " << m;
  }
}

// Sub-cell noise: +1, -1 on the two points of each cell along x (at h/4 and 3h/4) projects to
// zero on every node but the bar's two ends (each node gets 3/4 - 1/4 from one side and
// 1/4 - 3/4 from the other): PIC and XPIC(m) remove it from every point that the ends' non-zero
// V does not reach (m cells from them: each round trip Q spreads it by one node); FLIP (share 0)
// would keep it whole.
TEST(Xpic, RemovesTheNullSpaceNoiseAsPic) {
  constexpr int kCells = 16;
  Bar bar(kCells);
  const double h = bar.g.spacing[0];
  for (std::size_t p = 0; p < bar.pts.size(); ++p) {
    const double in_cell = std::fmod(bar.pts.x[p][0], h) / h;  // 0.25 or 0.75
    bar.pts.v[p] = Vec3(in_cell < 0.5 ? 1.0 : -1.0, 0, 0);
  }
  bar.project();
  for (const int m : {1, 2, 3, 5}) {
    const std::vector<Vec3> v = bar.update(m);
    int clean = 0;
    for (std::size_t p = 0; p < v.size(); ++p) {
      const double x = bar.pts.x[p][0];
      if (x < m * h || x > (kCells - m) * h) continue;
      ++clean;
      EXPECT_LT(v[p].norm(), 1e-12) << "m " << m << " point " << p;
    }
    EXPECT_EQ(clean, (kCells - 2 * m) * 8);
  }
}

// A smooth mode the grid resolves: the points' velocity interpolated from a nodal sine of 8
// cells per wavelength (no sub-cell part). On a periodic grid it is an eigenvector of the PIC
// round trip P (P maps the one-dimensional range of S at one wave number into itself) with some
// eigenvalue lambda: PIC damps it by e = 1 - lambda (here 0.11: PIC's diffusion, which XPIC
// is built to avoid), XPIC(m) by e^m. Measured over one wavelength in the middle of a 32-cell
// bar, which the ends' departure from periodicity does not reach within m <= 4 round trips:
// e^m to round-off (relative 1e-9).
TEST(Xpic, DampsAResolvedModeByThePowerOfPicsLoss) {
  Bar bar(32);
  const double h = bar.g.spacing[0];
  const double k = 2.0 * std::numbers::pi / (8.0 * h);
  std::vector<double> v0(bar.pts.size());
  for (std::size_t p = 0; p < bar.pts.size(); ++p) {
    v0[p] = 0.0;
    mpm::for_each_node(bar.g, bar.cache, p, [&](std::int64_t node_i, double S, const Vec3&) {
      v0[p] += S * std::sin(k * bar.g.node_position(node_i)[0]);
    });
    bar.pts.v[p] = Vec3(v0[p], 0, 0);
  }
  bar.project();
  auto loss = [&](int m) {
    const std::vector<Vec3> v = bar.update(m);
    double num = 0.0, den = 0.0;
    for (std::size_t p = 0; p < v.size(); ++p) {
      const double x = bar.pts.x[p][0];
      if (x < 12 * h || x > 20 * h) continue;
      num += (v[p][0] - v0[p]) * (v[p][0] - v0[p]);
      den += v0[p] * v0[p];
    }
    return std::sqrt(num / den);
  };
  const double e = loss(1);
  EXPECT_GT(e, 0.05);
  EXPECT_LT(e, 0.5);
  for (const int m : {2, 3, 4}) {
    const double expected = std::pow(e, m);
    EXPECT_NEAR(loss(m), expected, 1e-9 * expected) << "m " << m;
  }
}

// Linear momentum: Q keeps sum_i m_i w_i (it is a mass-weighted P2G of a G2P), so V* has V's
// momentum and the XPIC update keeps the points' momentum, as PIC does (no constraint here;
// round-off of sums of ~100 terms of order 1: 1e-13 relative).
TEST(Xpic, KeepsTheLinearMomentum) {
  Bar bar(12);
  Vec3 before = Vec3::Zero();
  for (std::size_t p = 0; p < bar.pts.size(); ++p) {
    bar.pts.v[p] = Vec3(std::sin(1.7 * p), std::cos(2.3 * p), std::sin(0.3 * p + 1.0));
    before += bar.pts.mass[p] * bar.pts.v[p];
  }
  bar.project();
  for (const int m : {2, 3, 6}) {
    const std::vector<Vec3> v = bar.update(m);
    Vec3 after = Vec3::Zero();
    for (std::size_t p = 0; p < v.size(); ++p) after += bar.pts.mass[p] * v[p];
    double scale = 0.0;
    for (std::size_t p = 0; p < v.size(); ++p) scale += bar.pts.mass[p] * bar.pts.v[p].norm();
    EXPECT_LT((after - before).norm(), 1e-13 * scale) << "m " << m;
  }
}

// A prescribed component (fields.fixed) stays V's in V*, whatever the order.
TEST(Xpic, KeepsThePrescribedComponents) {
  Bar bar(4);
  for (std::size_t p = 0; p < bar.pts.size(); ++p) {
    bar.pts.v[p] = Vec3(std::cos(3.0 * p), std::sin(5.0 * p), 0.5);
  }
  bar.project();
  const auto end = static_cast<std::size_t>(bar.g.node_index(0, 0, 0));
  bar.f.fixed[end] = 1u;                      // x prescribed
  bar.f.velocity[end] = Vec3(2.0, 0.0, 0.0);  // e.g. a moving platen's
  for (const int m : {2, 4}) {
    std::vector<Vec3> v_star;
    mpm::XpicScratch scratch;
    mpm::xpic_velocity(bar.g, bar.cache, bar.bins, bar.pts, bar.f, 1e-12, m, scratch, v_star);
    EXPECT_NEAR(v_star[end][0], 2.0, 1e-13) << "m " << m;
  }
}

// Enough points for the parallel loops (>= kMinParallelPoints): 1 and 2 threads, the same bits.
TEST(Xpic, SameBitsOnAnyNumberOfThreads) {
  Bar bar(600);  // 4,800 points
  ASSERT_GE(static_cast<std::int64_t>(bar.pts.size()), mpm::kMinParallelPoints);
  for (std::size_t p = 0; p < bar.pts.size(); ++p) {
    bar.pts.x[p] += 0.01 * Vec3(std::sin(1.3 * p), std::cos(0.7 * p), std::sin(2.9 * p));
    bar.pts.v[p] = Vec3(std::sin(0.37 * p), std::cos(0.11 * p), std::sin(0.05 * p));
  }
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Vec3>> out;
  for (const int n : {1, 2}) {
    omp_set_num_threads(n);
    Bar b(600);
    b.pts = bar.pts;
    b.project();
    out.push_back(b.update(3));
  }
  omp_set_num_threads(threads);
  EXPECT_EQ(out[0], out[1]);
}

// With grid positions the points move with the grid's own velocity S (V + dt a), the field whose
// gradient deforms the material, while their velocity takes V*'s PIC share: bit for bit the
// displacement of the update without V*.
TEST(Xpic, GridPositionsMoveWithTheGridsOwnVelocity) {
  Bar bar(8);
  for (std::size_t p = 0; p < bar.pts.size(); ++p) {
    bar.pts.v[p] = Vec3(std::sin(0.9 * p), 0.0, std::cos(0.4 * p));
  }
  bar.project();
  std::vector<Vec3> v_star;
  mpm::XpicScratch scratch;
  mpm::xpic_velocity(bar.g, bar.cache, bar.bins, bar.pts, bar.f, 1e-12, 3, scratch, v_star);
  mpm::MaterialPoints with_xpic = bar.pts;
  mpm::MaterialPoints without = bar.pts;
  mpm::g2p_update(bar.g, bar.cache, bar.f, 1.0, true, 1e-3, with_xpic, true, false, &v_star);
  mpm::g2p_update(bar.g, bar.cache, bar.f, 1.0, true, 1e-3, without, true, false);
  EXPECT_EQ(with_xpic.x, without.x);
  EXPECT_NE(with_xpic.v, without.v);
}
