// Verification of the frictional walls, reactions and time windows of the velocity constraints
// (docs/design/mpm.md, "Frictional boundaries and reactions"): a block sliding on a rough base, the
// platen reaction of the elastic single-cell triaxial, a gate removed at a given time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "common/state_store.hpp"

#include "mpm/boundary.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/material_points.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Mat3;
using common::Vec3;

struct Slide {
  double accel = 0.0;     ///< least-squares slope of the mean x velocity over [T/4, T] [m/s^2]
  double max_disp = 0.0;  ///< largest |mean x displacement| over the run [m]
};

// A 0.2 m elastic cube (nu = 0: no lateral stress) on a flat frictional base (a wall on the grid
// face z-), gravity tilted by theta in the x-z plane (the inclined plane in the grid's frame),
// from its geostatic state sigma_zz = -rho g cos(theta) (H - z), run to T without damping.
Slide slide(double theta, double mu, double T,
            mpm::WallContact contact = mpm::WallContact::no_penetration,
            bool wall_impulse = false) {
  const double g = 10.0, rho = 2000.0, H = 0.1;
  mpm::SolverConfig cfg;
  cfg.wall_impulse_on_points = wall_impulse;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.05), common::Vec3i(16, 4, 6)};
  cfg.gravity = Vec3(g * std::sin(theta), 0.0, -g * std::cos(theta));
  mpm::LinearElastic mat(1e7, 0.0, rho);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3(0.1, 0, 0), Vec3(0.5, 0.2, H), 2, rho, 0);
  double M = 0.0, x0 = 0.0;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    Mat3 s = Mat3::Zero();
    s(2, 2) = -rho * g * std::cos(theta) * (H - pts.x[p][2]);
    pts.stress[p] = s;
    mat.set_stress(pts.id[p], s);
    M += pts.mass[p];
    x0 += pts.mass[p] * pts.x[p][0];
  }
  mpm::Solver solver(cfg, pts, {&mat});
  mpm::VelocityConstraint base = mpm::face_constraint(cfg.grid, 2, -1, {false, false, false});
  base.wall = {2, -1, mu, contact};
  solver.add_constraint(base);
  // Least squares of v(t) on [T/4, T].
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  Slide r;
  while (solver.time() < T) {
    solver.step();
    double px = 0.0, mx = 0.0;
    for (std::size_t p = 0; p < solver.points().size(); ++p) {
      px += solver.points().mass[p] * solver.points().v[p][0];
      mx += solver.points().mass[p] * solver.points().x[p][0];
    }
    r.max_disp = std::max(r.max_disp, std::abs((mx - x0) / M));
    const double t = solver.time();
    if (t < 0.25 * T) continue;
    const double v = px / M;
    n += 1;
    st += t;
    sv += v;
    stt += t * t;
    stv += t * v;
  }
  r.accel = (n * stv - st * sv) / (n * stt - st * st);
  return r;
}

// tan(30 deg) = 0.577 > mu = 0.3: slides with a = g (sin - mu cos) = 2.402 m/s^2. 1 %: the
// friction is mu times the base nodes' normal force, which oscillates about the weight's normal
// component with the block's small elastic vibration (the block starts in vertical equilibrium
// but with no shear stress); the fit over 3/4 of the run averages it (measured 0.18 %).
// Unilateral contact (no_penetration), as a block on a plane: with a fixed (bilateral) base the
// nodes the friction moment lifts are held in tension, which gives no friction, while the others
// carry more than the weight: the total friction exceeds mu N (docs/design/mpm.md).
// The same with mpm.wall_impulse = "points" (measured 3e-5).
TEST(FrictionalWall, BlockSlidesWithCoulombAcceleration) {
  const double theta = 30.0 * std::numbers::pi / 180.0, mu = 0.3;
  const double exact = 10.0 * (std::sin(theta) - mu * std::cos(theta));
  for (const bool wall_impulse : {false, true}) {
    const Slide s = slide(theta, mu, 0.4, mpm::WallContact::no_penetration, wall_impulse);
    std::printf("sliding block (wall impulse %d): a = %.5f m/s^2, exact %.5f, error %.2e\n",
                wall_impulse, s.accel, exact, s.accel / exact - 1.0);
    EXPECT_NEAR(s.accel / exact, 1.0, 0.01);
  }
}

// tan(20 deg) = 0.364 < mu = 0.5 sticks, and so does a rough fixed base (mu = 1e6) at 30 deg.
// Sticking: the block's centre only moves by the elastic shear of the block, of order gamma H
// with gamma = rho g sin(theta) H / G (1.4e-5 m at 20 deg); 3 gamma H as the bound (the shear
// starts from zero and overshoots; measured 1.9 and 2.1 gamma H), against 0.19 m of sliding.
// The rough fixed base holds with mpm.wall_impulse = "points" too (measured 0.9 gamma H); the
// no_penetration base at mu = 0.5 does not (1.8 mm in 0.2 s, 130 gamma H: docs/design/mpm.md).
TEST(FrictionalWall, BlockSticksWhenTanThetaBelowMu) {
  const double t20 = 20.0 * std::numbers::pi / 180.0, t30 = 30.0 * std::numbers::pi / 180.0;
  const Slide s20 = slide(t20, 0.5, 0.2);
  const Slide rough_fixed = slide(t30, 1e6, 0.2, mpm::WallContact::fixed);
  const Slide rough_fixed_impulse = slide(t30, 1e6, 0.2, mpm::WallContact::fixed, true);
  std::printf(
      "sticking block: max |dx| = %.3e m (20 deg, mu 0.5), %.3e m (30 deg, rough, fixed),"
      " %.3e m (the same, wall impulse on the points)\n",
      s20.max_disp, rough_fixed.max_disp, rough_fixed_impulse.max_disp);
  // gamma H, gamma = rho g sin(theta) H / G (G = 5 MPa, H = 0.1 m).
  auto elastic = [](double theta) { return 2000.0 * 10.0 * std::sin(theta) * 0.01 / 5e6; };
  EXPECT_LT(s20.max_disp, 3.0 * elastic(t20));
  EXPECT_LT(rough_fixed.max_disp, 3.0 * elastic(t30));
  EXPECT_LT(rough_fixed_impulse.max_disp, 3.0 * elastic(t30));
}

// jobs/elastic_triaxial.toml: one cell, 8 elastic points at 100 kPa, platen z+ at -1 mm/s for
// 2 s, base z- fixed, 3-2-1 pins, 100 kPa on the lateral faces, damping 0.2. The platen reaction
// (force on the material) is sigma_zz times the current cross-section A (the material extent in
// x and y): within 0.5 % once the platen's start has passed (t > 0.1 s). What remains is known:
// the internal force integrates sigma over V / h while the material is F_zz h high, so R =
// sigma_zz A F_zz (0.2 % at the end), plus the platen start's transient (measured max 0.40 %);
// the base reacts with the opposite force (quasi-static: 1e-6 measured, 0.5 % allowed).
TEST(Reactions, PlatenReactionIsSigmaZzTimesAreaInElasticTriaxial) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i::Ones()};
  cfg.damping = 0.2;
  const Mat3 s0 = -1e5 * Mat3::Identity();
  mpm::LinearElastic mat(50e6, 0.3, 1696.0, s0);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), 2, 1696.0, 0);
  for (Mat3& s : pts.stress) s = s0;
  mpm::Solver solver(cfg, pts, {&mat});
  const double v = -1e-3;
  mpm::VelocityConstraint base = mpm::face_constraint(cfg.grid, 2, -1, {false, false, true});
  base.name = "base";
  solver.add_constraint(base);
  mpm::VelocityConstraint top =
      mpm::face_constraint(cfg.grid, 2, 1, {false, false, true}, Vec3(0, 0, v));
  top.name = "platen";
  solver.add_constraint(top);
  solver.add_constraint(mpm::node_constraint(cfg.grid, Vec3::Zero(), {true, true, false}));
  solver.add_constraint(mpm::node_constraint(cfg.grid, Vec3(1, 0, 0), {false, true, false}));
  for (int axis : {0, 1}) {
    for (int side : {-1, 1}) solver.add_traction({axis, side, 1e5, Vec3::Zero()});
  }
  ASSERT_EQ(solver.constraint_names()[2], "constraint_2");
  double worst = 0.0, worst_balance = 0.0;
  while (solver.time() < 2.0) {
    solver.step();
    if (solver.time() < 0.1) continue;
    double szz = 0.0;
    for (const Mat3& s : solver.points().stress) szz += s(2, 2) / 8.0;
    const mpm::MaterialExtent e = mpm::material_extent(solver.points());
    const double area = (e.hi[0] - e.lo[0]) * (e.hi[1] - e.lo[1]);
    const Vec3 r_top = solver.reactions()[1];
    const Vec3 r_base = solver.reactions()[0];
    worst = std::max(worst, std::abs(r_top[2] / (szz * area) - 1.0));
    worst_balance = std::max(worst_balance, std::abs(r_base[2] / r_top[2] + 1.0));
    EXPECT_EQ(r_top[0], 0.0);
  }
  std::printf("triaxial platen: max |R / (sigma_zz A) - 1| = %.3e, base/top balance %.3e\n", worst,
              worst_balance);
  EXPECT_LT(worst, 0.005);
  EXPECT_LT(worst_balance, 0.005);
  // Displacement: v t exactly (always active, constant velocity).
  EXPECT_EQ(solver.constraint_displacements()[1], Vec3(0, 0, v * solver.time()));
  EXPECT_EQ(solver.constraint_displacements()[0], Vec3::Zero());
}

// Column-collapse release: an elastic column (nu = 0.3) on a rough base, held on its x+ side by a
// gate (x fixed) until 0.05 s. Before: the gate pushes the column back (R_x < 0) and the front
// does not pass it; from 0.05 s the gate's reaction is exactly zero and the front moves out.
// A second, moving, windowed constraint on nodes far from the material integrates its velocity
// over its window only.
TEST(Reactions, GateStopsActingAtUntil) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.05), common::Vec3i(12, 2, 8)};
  cfg.gravity = Vec3(0, 0, -10);
  cfg.damping = 0.2;
  mpm::LinearElastic mat(1e6, 0.3, 2000.0);
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3(0.2, 0.1, 0.3), 2, 2000.0, 0);
  mpm::Solver solver(cfg, pts, {&mat});
  mpm::VelocityConstraint floor = mpm::face_constraint(cfg.grid, 2, -1, {false, false, false});
  floor.wall = {2, -1, 1e6, mpm::WallContact::fixed};
  solver.add_constraint(floor);
  solver.add_constraint(mpm::face_constraint(cfg.grid, 0, -1, {true, false, false}));
  mpm::VelocityConstraint gate{
      Vec3(0.2, -1, -1), Vec3(0.2, 1, 1), {true, false, false}, Vec3::Zero(), {}};
  gate.until = 0.05;
  gate.name = "gate";
  solver.add_constraint(gate);
  mpm::VelocityConstraint mover{
      Vec3(0.5, -1, -1), Vec3(0.6, 1, 1), {false, false, true}, Vec3(0, 0, 2.0), {}};
  mover.from = 0.02;
  mover.until = 0.04;
  solver.add_constraint(mover);
  double front_at_release = 0.0, min_rx = 0.0;
  double active_time = 0.0;
  auto front = [&] {
    double f = 0.0;
    for (const Vec3& x : solver.points().x) f = std::max(f, x[0]);
    return f;
  };
  const double front0 = front();
  while (solver.time() < 0.15) {
    const double t = solver.time();
    const double dt = solver.next_dt();
    solver.step();
    if (t >= 0.02 && t < 0.04) active_time += dt;
    const Vec3 r = solver.reactions()[2];
    if (t < 0.05) {
      min_rx = std::min(min_rx, r[0]);
      front_at_release = front();
    } else {
      EXPECT_EQ(r, Vec3::Zero()) << "t = " << t;
    }
  }
  std::printf("gate: front %.6f -> %.6f (release) -> %.6f m, min R_x %.3f N\n", front0,
              front_at_release, front(), min_rx);
  EXPECT_LT(min_rx, 0.0);
  // Held: the front moved less than 1e-5 m (the gate's node plane holds x); released: more than
  // 1e-4 m, the order of the column's elastic lateral expansion |sigma_xx| w / E = 0.26 mm.
  EXPECT_LT(front_at_release - front0, 1e-5);
  EXPECT_GT(front() - front_at_release, 1e-4);
  // The mover: 2 m/s over its active steps (holds no material: no reaction).
  EXPECT_NEAR(solver.constraint_displacements()[3][2], 2.0 * active_time, 1e-12);
  EXPECT_EQ(solver.reactions()[3], Vec3::Zero());
}

// A windowed constraint's displacement (state: saved as constraints/displacement) and a wall's
// reaction continue bit for bit across save/load; an always-active one (v t, no state) too.
TEST(Reactions, WindowedDisplacementContinuesAcrossCheckpoint) {
  auto build = [](mpm::LinearElastic& mat) {
    mpm::SolverConfig cfg;
    cfg.grid = {Vec3::Zero(), Vec3::Constant(0.05), common::Vec3i(8, 2, 4)};
    cfg.gravity = Vec3(3, 0, -10);
    mpm::MaterialPoints pts;
    mpm::fill_box(pts, cfg.grid, Vec3(0.1, 0, 0), Vec3(0.2, 0.1, 0.1), 2, 2000.0, 0);
    auto s = std::make_unique<mpm::Solver>(cfg, pts, std::vector<mpm::MaterialModel*>{&mat});
    mpm::VelocityConstraint base = mpm::face_constraint(cfg.grid, 2, -1, {false, false, false});
    base.wall = {2, -1, 0.2, mpm::WallContact::no_penetration};
    s->add_constraint(base);
    mpm::VelocityConstraint mover{
        Vec3(0.3, -1, -1), Vec3(0.4, 1, 1), {false, false, true}, Vec3(0, 0, 0.5), {}};
    mover.from = 2e-3;
    mover.until = 6e-3;
    s->add_constraint(mover);
    s->add_constraint(mpm::face_constraint(cfg.grid, 0, 1, {true, false, false}, Vec3(-0.1, 0, 0)));
    return s;
  };
  mpm::LinearElastic mat_a(1e6, 0.3, 2000.0);
  auto a = build(mat_a);
  while (a->time() < 4e-3) a->step();
  common::StateStore store;
  a->save(store);
  mat_a.save(store, "material/0/");
  EXPECT_TRUE(store.has("constraints/displacement"));
  const std::int64_t half = a->step_count();
  a->run(half);
  mpm::LinearElastic mat_b(1e6, 0.3, 2000.0);
  auto b = build(mat_b);
  b->load(store);
  mat_b.load(store, "material/0/");
  b->run(half);
  ASSERT_EQ(a->time(), b->time());
  EXPECT_GT(a->time(), 6e-3);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(a->constraint_displacements()[k], b->constraint_displacements()[k]) << k;
    EXPECT_EQ(a->reactions()[k], b->reactions()[k]) << k;
  }
  EXPECT_NEAR(a->constraint_displacements()[1][2], 0.5 * 4e-3, 0.5 * a->next_dt());
  EXPECT_EQ(a->constraint_displacements()[2], Vec3(-0.1 * a->time(), 0, 0));
}

}  // namespace

namespace {

// A material without stress (an RVE that has lost every contact): L changes nothing.
class NoStress final : public mpm::MaterialModel {
 public:
  void update_stress(std::span<const std::int64_t>, std::span<const common::Mat3>, double,
                     std::span<common::Mat3> stress) override {
    for (common::Mat3& s : stress) s.setZero();
  }
  [[nodiscard]] double wave_speed() const override { return 1.0; }
};

struct Landing {
  common::Vec3 v_bottom;   ///< velocity of the first point at the end [m/s]
  common::Vec3 momentum;   ///< sum m_p v_p at the end [kg m/s]
  common::Vec3 momentum0;  ///< at the start
  common::Vec3 impulse;    ///< sum over the steps of dt x the base's reaction [N s]
  double lowest = 0.0;     ///< lowest point z at the end [m]
};

// A layer of stress-free points (pure FLIP, positions with the grid velocity, no gravity), one
// per cell in the bottom cell row of a rough base, all moving at (0.3, 0, -1) m/s into it: the
// collapse's front points on its base (docs/validation/column_collapse.md). One point per cell across the
// layer: two points above one another could hold a FLIP mode the base nodes do not see
// (velocities whose momenta cancel there), which no wall can take (docs/design/mpm.md).
Landing land(bool wall_impulse_on_points) {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(4, 1, 3)};
  cfg.dt = 1e-3;
  cfg.grid_positions = true;
  cfg.wall_impulse_on_points = wall_impulse_on_points;
  NoStress mat;
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, cfg.grid, Vec3(0.1, 0.0, 0.0), Vec3(0.3, 0.1, 0.1), 1, 1000.0, 0);
  Landing r{};
  for (std::size_t p = 0; p < pts.size(); ++p) {
    pts.v[p] = Vec3(0.3, 0.0, -1.0);
    r.momentum0 += pts.mass[p] * pts.v[p];
  }
  mpm::Solver solver(cfg, pts, {&mat});
  mpm::VelocityConstraint base = mpm::face_constraint(cfg.grid, 2, -1, {false, false, false});
  base.wall = {2, -1, 10.0, mpm::WallContact::fixed};
  solver.add_constraint(base);
  for (int k = 0; k < 200; ++k) {
    solver.step();
    r.impulse += cfg.dt * solver.reactions()[0];
  }
  const mpm::MaterialPoints& q = solver.points();
  r.v_bottom = q.v[0];
  r.lowest = 1.0;
  for (std::size_t p = 0; p < q.size(); ++p) {
    r.momentum += q.mass[p] * q.v[p];
    r.lowest = std::min(r.lowest, q.x[p][2]);
  }
  return r;
}

}  // namespace

// mpm.wall_impulse: "grid" (default): the base takes the nodes' velocity at the momentum stage
// only, so the points keep (0.3, 0, -1) m/s for ever, a velocity that never moves them, and the
// base reports no force. "points": the same correction reaches the points' FLIP velocities, the
// layer comes to rest on the rough base, and the base's reaction is the force that stopped it:
// the points' momentum change equals the reaction's impulse (Newton's third law; 1e-12 of the
// initial momentum: sums of 200 steps' rounding).
TEST(FrictionalWall, WallImpulseReachesThePointsOnlyWhenAsked) {
  const Landing g = land(false);
  EXPECT_EQ(g.v_bottom, Vec3(0.3, 0.0, -1.0));
  EXPECT_EQ(g.impulse, Vec3::Zero());
  EXPECT_GE(g.lowest, 0.0);
  const Landing p = land(true);
  std::printf("wall_impulse points: v %.3g %.3g %.3g m/s, momentum %.3g -> %.3g, impulse %.3g\n",
              p.v_bottom[0], p.v_bottom[1], p.v_bottom[2], p.momentum0.norm(), p.momentum.norm(),
              p.impulse.norm());
  EXPECT_LT(p.v_bottom.norm(), 1e-3);
  EXPECT_LT(p.momentum.norm(), 1e-3 * p.momentum0.norm());
  EXPECT_LT((p.momentum - p.momentum0 - p.impulse).norm(), 1e-12 * p.momentum0.norm());
  EXPECT_GT(p.impulse[2], 0.0);  // the base pushes up
  EXPECT_LT(p.impulse[0], 0.0);  // and holds the slip back
  EXPECT_GE(p.lowest, 0.0);
}
