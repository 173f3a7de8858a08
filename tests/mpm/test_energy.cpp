// Tests of energy.hpp (kinetic energy, stress power, the quasi-static watch) and of the solver's
// internal work: its value for a homogeneous compression, and its checkpoint field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "common/state_store.hpp"
#include "mpm/energy.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/solver.hpp"

namespace {

using common::Mat3;
using common::Vec3;

mpm::MaterialPoints two_points() {
  mpm::MaterialPoints pts;
  pts.add(0, Vec3::Zero(), 2.0, 0.5, Vec3::Constant(0.5), 0);
  pts.add(1, Vec3::Ones(), 3.0, 0.25, Vec3::Constant(0.5), 0);
  return pts;
}

TEST(Energy, KineticEnergyScalesWithTheInertia) {
  mpm::MaterialPoints pts = two_points();
  pts.v[0] = Vec3(1, 2, 2);  // |v|^2 = 9
  pts.v[1] = Vec3(0, 0, -2);
  const double ke = 0.5 * (2.0 * 9.0 + 3.0 * 4.0);
  EXPECT_DOUBLE_EQ(mpm::kinetic_energy(pts, 1.0), ke);
  EXPECT_DOUBLE_EQ(mpm::kinetic_energy(pts, 100.0), 100.0 * ke);
}

// Compression against a compressive stress does positive work; a spin does none.
TEST(Energy, StressPowerIsCompressionPositiveAndSpinFree) {
  mpm::MaterialPoints pts = two_points();
  pts.stress[0] = -1e3 * Mat3::Identity();
  pts.L[0] = Mat3::Zero();
  pts.L[0](2, 2) = -0.1;
  pts.L[0](0, 1) = 0.7;  // spin 0.35 + shear rate 0.35: sigma is isotropic, no shear work
  pts.L[0](1, 0) = -0.7;
  pts.stress[1] = Mat3::Zero();
  pts.stress[1](0, 1) = pts.stress[1](1, 0) = 2e3;
  pts.L[1] = Mat3::Zero();
  pts.L[1](0, 1) = 0.2;  // D_xy = D_yx = 0.1
  const double expected = 0.5 * 1e3 * 0.1 + 0.25 * 2.0 * 2e3 * 0.1;
  EXPECT_DOUBLE_EQ(mpm::stress_power(pts), expected);
}

TEST(Energy, RatioEdgeCases) {
  EXPECT_EQ((mpm::Energies{0.0, 0.0}).ratio(), 0.0);
  EXPECT_EQ((mpm::Energies{1.0, 0.0}).ratio(), std::numeric_limits<double>::infinity());
  EXPECT_EQ((mpm::Energies{1.0, -2.0}).ratio(), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ((mpm::Energies{1.0, 4.0}).ratio(), 0.25);
}

// Not watched before 5 % of the end time; warns once, naming the step and the time; never
// without mass scaling (but the ratio is still tracked).
TEST(Energy, QuasiStaticWatchWarnsOnceAfterTheWarmUp) {
  mpm::QuasiStaticWatch watch(0.01, 100.0, 10.0);
  EXPECT_TRUE(watch.observe(1, 0.4, {1.0, 1.0}).empty());  // before 0.5 s
  EXPECT_EQ(watch.max_ratio(), 0.0);
  EXPECT_TRUE(watch.observe(2, 0.6, {0.005, 1.0}).empty());
  const std::string w = watch.observe(3, 0.7, {0.02, 1.0});
  EXPECT_NE(w.find("mpm step 3 (t = 0.7 s)"), std::string::npos) << w;
  EXPECT_NE(w.find("no longer quasi-static"), std::string::npos) << w;
  EXPECT_TRUE(watch.warned());
  EXPECT_TRUE(watch.observe(4, 0.8, {0.5, 1.0}).empty());
  EXPECT_DOUBLE_EQ(watch.max_ratio(), 0.5);

  mpm::QuasiStaticWatch off(0.01, 1.0, 10.0);
  EXPECT_TRUE(off.observe(3, 0.7, {0.5, 1.0}).empty());
  EXPECT_DOUBLE_EQ(off.max_ratio(), 0.5);
}

/// One cell, 8 points, E = 1e6, nu = 0, initial stress -p I, every node moving with the
/// homogeneous field v = (0, 0, -r z): uniaxial compression at rate r, no inertia involved.
struct Uniaxial {
  mpm::SolverConfig cfg;
  mpm::LinearElastic material{1e6, 0.0, 1000.0, -1e4 * Mat3::Identity()};
  std::unique_ptr<mpm::Solver> solver;
  Uniaxial() {
    cfg.grid = {Vec3::Zero(), Vec3::Ones(), common::Vec3i(1, 1, 1)};
    cfg.dt = 1e-4;
    mpm::MaterialPoints pts;
    mpm::fill_box(pts, cfg.grid, Vec3::Zero(), Vec3::Ones(), 2, 1000.0, 0);
    for (Mat3& s : pts.stress) s = -1e4 * Mat3::Identity();
    solver = std::make_unique<mpm::Solver>(cfg, pts, std::vector<mpm::MaterialModel*>{&material});
    mpm::VelocityConstraint c{
        Vec3::Constant(-1), Vec3::Constant(2), {true, true, true}, Vec3::Zero(), {}};
    c.field = [](const Vec3& x, double) { return Vec3(0, 0, -0.1 * x[2]); };
    solver->add_constraint(c);
  }
};

// The work of sigma_zz = -p + E eps along eps from 0 to e (e < 0) on the current volume
// V0 (1 + eps): W = -p e + (E - p) e^2 / 2 + E e^3 / 3 (per m^3). Tolerance 1e-5 relative: the
// solver's volume det(I + L dt) per step and its trapezoid on the stress power differ from that
// integral by O(dt r) (measured 1.7e-7 for 100 steps of strain 1e-5 each).
TEST(Energy, SolverInternalWorkOfUniaxialCompression) {
  Uniaxial u;
  u.solver->run(100);
  double eps = 0.0;
  for (int k = 0; k < 100; ++k) eps += 1e-4 * -0.1;
  const double p = 1e4, E = 1e6;
  auto W = [&](double e) { return -(p * e + (p - E) * e * e / 2 - E * e * e * e / 3); };
  const double work = u.solver->energies().internal_work;
  std::printf("uniaxial internal work %.10g J, exact %.10g J\n", work, W(eps));
  EXPECT_GT(work, 0.0);
  EXPECT_NEAR(work, W(eps), 1e-5 * W(eps));
}

// solver/internal_work is saved and read back; a checkpoint without it (written before the
// energy accounting existed) restarts the work from 0.
TEST(Energy, InternalWorkIsCheckpointedAndOptional) {
  Uniaxial a;
  a.solver->run(10);
  common::StateStore store;
  a.solver->save(store);
  Uniaxial b;
  b.solver->load(store);
  EXPECT_EQ(b.solver->energies().internal_work, a.solver->energies().internal_work);
  EXPECT_GT(b.solver->energies().internal_work, 0.0);

  common::StateStore old;
  for (const auto& [name, field] : store.fields()) {
    if (name == "solver/internal_work") continue;
    std::visit([&](const auto& v) { old.write(name, v); }, field);
  }
  Uniaxial c;
  c.solver->run(3);
  c.solver->load(old);
  EXPECT_EQ(c.solver->energies().internal_work, 0.0);
  EXPECT_EQ(c.solver->step_count(), 10);
}

}  // namespace
