// Tests of transfers.hpp and grid_solve.hpp: conservation in P2G, colouring, bit-for-bit
// independence of the OpenMP thread count, mass threshold, Cundall damping (eq. 8).
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <set>

#include "mpm/grid_solve.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"
#include "mpm/transfers.hpp"

namespace {

using common::Vec3;

// Points filling cells 1 .. cells - 2 of every axis, jittered, random velocities.
mpm::MaterialPoints jittered_block(const mpm::Grid& g, int ppc, unsigned seed) {
  mpm::MaterialPoints pts;
  const Vec3 hi = (g.cells.cast<double>() - Vec3::Ones()).cwiseProduct(g.spacing);
  mpm::fill_box(pts, g, g.spacing, hi, ppc, 1000.0, 0);
  std::srand(seed);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    pts.x[p] += 0.2 * g.spacing[0] / ppc * Vec3::Random();
    pts.v[p] = Vec3::Random();
  }
  return pts;
}

// Every point in exactly one bin; bins of a colour touch disjoint nodes.
void expect_colours_disjoint(const mpm::Grid& g, const mpm::StencilCache& cache,
                             const mpm::PointBins& bins) {
  const std::array<int, 3> ns = cache.width;
  for (const auto& colour : bins.by_colour) {
    std::set<std::int64_t> nodes;
    for (auto b : colour) {
      const common::Vec3i base = g.node_ijk(bins.key[b]);
      for (int k = 0; k < ns[2]; ++k)
        for (int j = 0; j < ns[1]; ++j)
          for (int i = 0; i < ns[0]; ++i)
            EXPECT_TRUE(nodes.insert(g.node_index(base[0] + i, base[1] + j, base[2] + k)).second);
    }
  }
}

class Transfers : public ::testing::TestWithParam<mpm::ShapeKind> {};

TEST_P(Transfers, P2GConservesMassMomentumAndGravity) {
  mpm::Grid g{Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(7, 6, 6)};
  mpm::MaterialPoints pts = jittered_block(g, 2, 3);
  mpm::StencilCache cache;
  mpm::PointBins bins;
  mpm::GridFields f;
  f.resize(g);
  ASSERT_EQ(mpm::compute_stencils(GetParam(), g, pts, cache), -1);
  mpm::bin_points(g, cache, bins);
  mpm::activate_nodes(g, cache, bins, f);
  const Vec3 grav(0, 0, -9.81);
  mpm::p2g_mass_momentum(g, cache, bins, pts, grav, f);
  double m_p = 0, m_i = 0;
  Vec3 mv_p = Vec3::Zero(), mv_i = Vec3::Zero(), fg_i = Vec3::Zero();
  for (std::size_t p = 0; p < pts.size(); ++p) {
    m_p += pts.mass[p];
    mv_p += pts.mass[p] * pts.v[p];
  }
  for (auto i : f.active) {
    m_i += f.mass[i];
    mv_i += f.momentum[i];
    fg_i += f.force[i];
  }
  // Partition of unity: conserved to round-off (sums of ~1e3 terms, relative 1e-13).
  EXPECT_NEAR(m_i, m_p, 1e-13 * m_p);
  EXPECT_LT((mv_i - mv_p).norm(), 1e-13 * m_p);
  EXPECT_LT((fg_i - m_p * grav).norm(), 1e-13 * m_p * 9.81);
  EXPECT_EQ(bins.order.size(), pts.size());
  expect_colours_disjoint(g, cache, bins);
}

// A one-cell-thick grid (plane strain, thickness y): uGIMP in x and z, linear through y (its
// 3-node stencil would need 3 node planes, the grid has 2): the stencils stay inside the grid,
// P2G conserves mass and momentum, and bins of a colour touch disjoint nodes (2 colours in y).
TEST(Transfers, PlaneStrainUgimpIsLinearThroughTheThickness) {
  mpm::Grid g{Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(7, 1, 6)};
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, g, Vec3(0.1, 0.0, 0.1), Vec3(0.6, 0.1, 0.5), common::Vec3i(2, 1, 2), 1000.0,
                0);
  std::srand(5);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const Vec3 r = Vec3::Random();
    pts.x[p] += 0.04 * Vec3(r[0], 0.5 * r[1], r[2]);  // y stays inside the one cell
    pts.v[p] = Vec3::Random();
  }
  mpm::StencilCache cache;
  mpm::PointBins bins;
  mpm::GridFields f;
  f.resize(g);
  // Without the linear thickness the uGIMP stencil leaves the one-cell grid.
  EXPECT_GE(mpm::compute_stencils(mpm::ShapeKind::ugimp, g, pts, cache), 0);
  ASSERT_EQ(mpm::compute_stencils(mpm::ShapeKind::ugimp, g, pts, cache, 1), -1);
  EXPECT_EQ(cache.width, (std::array<int, 3>{3, 2, 3}));
  for (std::size_t p = 0; p < pts.size(); ++p) {
    // Linear in y: nodes 0 and 1, weights 1 - y/h and y/h; the third entry unused (zero).
    const double y = pts.x[p][1] / g.spacing[1];
    EXPECT_EQ(cache.base[p][1], 0);
    EXPECT_NEAR(cache.w[p * 9 + 3], 1.0 - y, 1e-15);
    EXPECT_NEAR(cache.w[p * 9 + 4], y, 1e-15);
    EXPECT_EQ(cache.w[p * 9 + 5], 0.0);
    // uGIMP in x: a 3-node stencil whose weights sum to one.
    EXPECT_NEAR(cache.w[p * 9 + 0] + cache.w[p * 9 + 1] + cache.w[p * 9 + 2], 1.0, 1e-14);
  }
  mpm::bin_points(g, cache, bins);
  EXPECT_EQ(bins.by_colour.size(), 18u);
  mpm::activate_nodes(g, cache, bins, f);
  mpm::p2g_mass_momentum(g, cache, bins, pts, Vec3::Zero(), f);
  double m_p = 0, m_i = 0;
  Vec3 mv_p = Vec3::Zero(), mv_i = Vec3::Zero();
  for (std::size_t p = 0; p < pts.size(); ++p) {
    m_p += pts.mass[p];
    mv_p += pts.mass[p] * pts.v[p];
  }
  for (auto i : f.active) {
    EXPECT_LE(g.node_ijk(i)[1], 1);
    m_i += f.mass[i];
    mv_i += f.momentum[i];
  }
  EXPECT_NEAR(m_i, m_p, 1e-13 * m_p);
  EXPECT_LT((mv_i - mv_p).norm(), 1e-13 * m_p);
  expect_colours_disjoint(g, cache, bins);
}

TEST_P(Transfers, StepIsBitForBitIndependentOfThreadCount) {
  // 12 x 10 x 8 cells x 8 points = 7680 points: above kMinParallelPoints, so loops run threaded.
  // Mass scaling on, and the energy sums (terms in parallel, added in slot order) compared too.
  mpm::Grid g{Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(14, 12, 10)};
  mpm::Energies energies;
  auto run = [&](int threads) {
    mpm::LinearElastic mat(1e5, 0.3, 1000.0);
    mpm::SolverConfig cfg;
    cfg.grid = g;
    cfg.shape = GetParam();
    cfg.gravity = Vec3(0, 0, -9.81);
    cfg.cfl = 0.4;
    cfg.damping = 0.1;
    cfg.mass_scaling = 10.0;
    mpm::Solver s(cfg, jittered_block(g, 2, 5), {&mat});
    s.add_constraint({Vec3(-1, -1, -1), Vec3(1, 1, 0.15), {true, true, true}, Vec3::Zero(), {}});
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    EXPECT_GE(static_cast<std::int64_t>(s.points().size()), mpm::kMinParallelPoints);
    s.run(4);
    energies = s.energies();
    omp_set_num_threads(saved);
    return s.points();
  };
  const mpm::MaterialPoints a = run(1);
  const mpm::Energies e1 = energies;
  EXPECT_GT(e1.kinetic, 0.0);
  EXPECT_NE(e1.internal_work, 0.0);
  for (int threads : {2, 3}) {
    const mpm::MaterialPoints b = run(threads);
    EXPECT_EQ(energies.kinetic, e1.kinetic) << threads << " threads";
    EXPECT_EQ(energies.internal_work, e1.internal_work) << threads << " threads";
    for (std::size_t p = 0; p < a.size(); ++p) {
      ASSERT_EQ(a.x[p], b.x[p]) << threads << " threads, point " << p;
      ASSERT_EQ(a.v[p], b.v[p]);
      ASSERT_EQ(a.stress[p], b.stress[p]);
      ASSERT_EQ(a.volume[p], b.volume[p]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, Transfers,
                         ::testing::Values(mpm::ShapeKind::linear, mpm::ShapeKind::ugimp,
                                           mpm::ShapeKind::bspline2),
                         [](const auto& param_info) {
                           return std::string(mpm::to_string(param_info.param));
                         });

TEST(GridSolve, CundallDampingVectorAndComponent) {
  mpm::Grid g{Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  mpm::GridFields f;
  f.resize(g);
  f.active = {0, 1};
  f.is_active[0] = f.is_active[1] = 1;
  f.mass[0] = 2.0;
  f.mass[1] = 1e-12;  // below the threshold
  f.force[0] = Vec3(3, 4, 0);
  f.force[1] = Vec3(1, 1, 1);
  f.velocity[0] = Vec3(0, 2, 0);
  mpm::compute_nodal_acceleration(1e-6, 0.5, mpm::DampingMode::cundall_vector, f);
  // Eq. 8: (f - D |f| v/|v|) / m = ((3, 4, 0) - 0.5 * 5 * (0, 1, 0)) / 2.
  EXPECT_EQ(f.acceleration[0], Vec3(1.5, 0.75, 0.0));
  EXPECT_EQ(f.acceleration[1], Vec3::Zero());
  mpm::compute_nodal_acceleration(1e-6, 0.5, mpm::DampingMode::cundall_component, f);
  // Per component: x has v_x = 0, no damping; y: (4 - 0.5 * 4) / 2.
  EXPECT_EQ(f.acceleration[0], Vec3(1.5, 1.0, 0.0));
  // No velocity: no damping at all.
  f.velocity[0].setZero();
  mpm::compute_nodal_acceleration(1e-6, 0.5, mpm::DampingMode::cundall_vector, f);
  EXPECT_EQ(f.acceleration[0], Vec3(1.5, 2.0, 0.0));
}

TEST(GridSolve, MassThresholdZeroesLightNodes) {
  mpm::Grid g{Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
  mpm::GridFields f;
  f.resize(g);
  f.active = {0, 1};
  f.is_active[0] = f.is_active[1] = 1;
  f.mass[0] = 1.0;
  f.mass[1] = 1e-9;
  f.momentum[0] = Vec3(1, 2, 3);
  f.momentum[1] = Vec3(1, 1, 1);
  const double thr = 1e-6 * mpm::typical_nodal_mass(f);
  mpm::compute_nodal_velocity(thr, f);
  EXPECT_EQ(f.velocity[0], Vec3(1, 2, 3));
  EXPECT_EQ(f.velocity[1], Vec3::Zero());
}

// One point in a column of two unit cells whose nodes are at rest (velocity and acceleration
// zero): what G2P does to the point's own velocity and position.
struct OnePointOnAGridAtRest {
  mpm::Grid g{Vec3::Zero(), Vec3::Constant(1.0), common::Vec3i(1, 1, 2)};
  mpm::MaterialPoints pts;
  mpm::StencilCache cache;
  mpm::GridFields f;
  OnePointOnAGridAtRest(const Vec3& x, const Vec3& v) {
    mpm::fill_box(pts, g, Vec3::Zero(), Vec3::Ones(), 1, 1000.0, 0);
    pts.x[0] = x;
    pts.v[0] = v;
    f.resize(g);
    EXPECT_EQ(mpm::compute_stencils(mpm::ShapeKind::linear, g, pts, cache), -1);
    for (auto& a : f.velocity) a = Vec3::Zero();
    for (auto& a : f.acceleration) a = Vec3::Zero();
  }
};

}  // namespace

// Position update (SolverConfig::grid_positions): a point just above a rigid base (its nodes held
// at zero velocity) with a downward FLIP velocity. Moving with v_p carries it through the base in
// one step; moving with the grid velocity (here zero at every node) leaves it in place, while its
// velocity update is the same in both modes (exact: the same expressions).
TEST(Transfers, GridPositionsKeepAPointAboveAHeldBase) {
  for (const bool grid_positions : {false, true}) {
    OnePointOnAGridAtRest s(Vec3(0.5, 0.5, 0.05), Vec3(0.0, 0.0, -5.0));
    mpm::MaterialPoints& pts = s.pts;
    mpm::g2p_update(s.g, s.cache, s.f, 0.0, true, 0.02, pts, grid_positions);
    EXPECT_EQ(pts.v[0], Vec3(0.0, 0.0, -5.0));
    if (grid_positions) {
      EXPECT_EQ(pts.x[0], Vec3(0.5, 0.5, 0.05));
    } else {
      EXPECT_NEAR(pts.x[0][2], 0.05 - 0.1, 1e-15);  // below the base: what the option prevents
    }
  }
}

// mpm.pic_time: the FLIP part of a point's velocity relaxes towards the grid's as exp(-t /
// pic_time), the same over one step of dt as over four of dt / 4; a share per step (mpm.flip)
// damps four short steps more than one long one (which is why it is not mesh-independent).
TEST(Transfers, PicShareRelaxesInTimeWhateverTheStep) {
  EXPECT_EQ(mpm::pic_share(0.95, 0.0, 1e-3), 1.0 - 0.95);
  EXPECT_EQ(mpm::pic_share(1.0, 0.0, 1e-3), 0.0);
  auto relax = [](double share_of_step(double), double dt, int steps) {
    OnePointOnAGridAtRest s(Vec3(0.5, 0.5, 0.5), Vec3(1.0, 0.0, -5.0));  // v_pic = 0
    for (int k = 0; k < steps; ++k) {
      mpm::g2p_update(s.g, s.cache, s.f, share_of_step(dt), true, dt, s.pts, true);
    }
    return s.pts.v[0];
  };
  constexpr double kTau = 0.05;
  auto in_time = [](double dt) { return mpm::pic_share(1.0, kTau, dt); };
  auto per_step = [](double dt) { return mpm::pic_share(0.9, 0.0, dt); };
  const Vec3 long_steps = relax(in_time, 0.02, 5);
  const Vec3 short_steps = relax(in_time, 0.005, 20);
  EXPECT_NEAR(long_steps[2], -5.0 * std::exp(-0.1 / kTau), 1e-12);
  EXPECT_NEAR(short_steps[2], long_steps[2], 1e-12);
  EXPECT_NEAR(short_steps[0], long_steps[0], 1e-13);
  // The share per step: 0.9^5 against 0.9^20 of the FLIP part left after the same time.
  EXPECT_GT(std::abs(relax(per_step, 0.005, 20)[2] - relax(per_step, 0.02, 5)[2]), 1.0);
}
