// Tests of gradient_regularisation.hpp: a homogeneous deformation stores no strain, a wave of
// strain rate is resisted by 1 - exp(-k^2 l^2 / 2) of itself (short waves fully, long ones not),
// the added stress does the energy's power, and in the solver the material keeps its own L, the
// state restarts bit for bit and the configuration is refused without its modulus.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <span>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "mpm/gradient_regularisation.hpp"
#include "mpm/linear_elastic.hpp"
#include "mpm/nonlocal_average.hpp"
#include "mpm/solver.hpp"
#include "plane_lattice.hpp"

namespace {

using common::Mat3;
using common::Vec3;

TEST(GradientRegularisation, HomogeneousDeformationStoresNoStrain) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> vol;
  for (int p = 0; p < 200; ++p) {
    x.emplace_back(u(rng), 0.0, u(rng));
    vol.push_back(0.5 + u(rng));
  }
  const std::vector<std::int32_t> material(x.size(), 0);
  Mat3 L;
  L << 0.3, 1.0, -0.2, 0.0, 0.1, 0.4, 0.7, -0.5, -0.6;  // stretching and spin
  const std::vector<Mat3> Ls(x.size(), L);
  for (const auto kind : {mpm::AverageKind::pairs, mpm::AverageKind::lattice}) {
    mpm::GradientRegularisation reg(0.05, 1e6, kind);
    for (int step = 0; step < 5; ++step) {
      const double work = reg.update(x, vol, material, Ls, 0.01);
      EXPECT_LT(std::abs(work), 1e-18);
    }
    for (const Mat3& e : reg.strain()) EXPECT_LT(e.norm(), 1e-16);
    std::vector<Mat3> stress(x.size(), Mat3::Identity());
    reg.add_force_stress(x, vol, material, stress);
    // H e ~ 1e6 * 1e-17: a few 1e-11 Pa on a unit stress.
    for (const Mat3& s : stress) EXPECT_LT((s - Mat3::Identity()).norm(), 1e-9);
  }
}

TEST(GradientRegularisation, ShortWavesAreResistedLongWavesAreFree) {
  const double l = 0.01, h = l / 4.0;
  for (const auto kind : {mpm::AverageKind::pairs, mpm::AverageKind::lattice}) {
  for (const double lambda : {4.0 * l, 20.0 * l}) {
    std::vector<Vec3> x;
    std::vector<double> vol;
    // Narrow in x, long in z: every point within lambda of z = 0 has its whole kernel.
    mpm_test::plane_lattice(33, static_cast<int>(2.0 * (lambda + 4.0 * l) / h) + 1, h, x, vol);
    const std::vector<std::int32_t> material(x.size(), 0);
    const double k = 2.0 * M_PI / lambda;
    std::vector<Mat3> L(x.size(), Mat3::Zero());
    for (std::size_t p = 0; p < x.size(); ++p) L[p](0, 0) = std::cos(k * x[p][2]);
    mpm::GradientRegularisation reg(l, 1e6, kind);
    reg.update(x, vol, material, L, 1.0);
    // The Gaussian's transform: e = (1 - exp(-k^2 l^2 / 2)) D. Tolerance 0.01: the cut at 3 l
    // (1.1 % of the kernel's weight) and the lattice's sampling; measured below 2e-3.
    const double expected = 1.0 - std::exp(-0.5 * k * k * l * l);
    int checked = 0;
    for (std::size_t p = 0; p < x.size(); ++p) {
      if (std::abs(x[p][0]) < 0.5 * h && std::abs(x[p][2]) < 0.5 * h) {
        EXPECT_NEAR(reg.strain()[p](0, 0), expected, 0.01)
            << "lambda / l = " << lambda / l << ", " << common::name_of(mpm::kAverageKindNames, kind);
        ++checked;
      }
    }
    EXPECT_EQ(checked, 1);
  }
  }
}

TEST(GradientRegularisation, TheAddedStressDoesTheEnergysPower) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> vol;
  std::vector<Mat3> e, L;
  for (int p = 0; p < 300; ++p) {
    x.emplace_back(u(rng), 0.0, u(rng));
    vol.push_back(1.2 + u(rng));
    Mat3 a = Mat3::NullaryExpr([&] { return u(rng); });
    e.push_back(0.5 * (a + a.transpose()));
    L.push_back(Mat3::NullaryExpr([&] { return u(rng); }));
  }
  const std::vector<std::int32_t> material(x.size(), 0);
  const double H = 3e5;
  mpm::GradientRegularisation reg(0.3, H, mpm::AverageKind::pairs);
  reg.set_strain(e);
  std::vector<Mat3> added(x.size(), Mat3::Zero());
  reg.add_force_stress(x, vol, material, added);
  // The energy's power, H e : (D - Dbar), against the forces' power on the points' own D.
  std::vector<Mat3> D, Dbar;
  for (const Mat3& l : L) D.push_back(0.5 * (l + l.transpose()));
  mpm::NonlocalAverage(0.3).apply(x, vol, material, D, Dbar);
  double energy = 0.0, forces = 0.0, scale = 0.0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    energy += vol[p] * H * e[p].cwiseProduct(D[p] - Dbar[p]).sum();
    forces += vol[p] * added[p].cwiseProduct(L[p]).sum();
    scale += vol[p] * H * e[p].norm() * D[p].norm();
  }
  EXPECT_NEAR(forces, energy, 1e-13 * scale);
  EXPECT_GT(std::abs(energy), 1e-3 * scale);  // not a trivial zero
}

/// LinearElastic that keeps the L it was given in its last update.
class RecordingElastic final : public mpm::MaterialModel {
 public:
  RecordingElastic() : inner_(10e6, 0.25, 2000.0) {}
  void update_stress(std::span<const std::int64_t> ids, std::span<const Mat3> L, double dt,
                     std::span<Mat3> stress) override {
    seen.assign(L.begin(), L.end());
    inner_.update_stress(ids, L, dt, stress);
  }
  [[nodiscard]] double wave_speed() const override { return inner_.wave_speed(); }
  void save(common::StateWriter& w) const { inner_.save(w, "material/0/"); }
  void load(const common::StateReader& r) { inner_.load(r, "material/0/"); }
  std::vector<Mat3> seen;

 private:
  mpm::LinearElastic inner_;
};

mpm::SolverConfig band_config() {
  mpm::SolverConfig cfg;
  cfg.grid = {Vec3::Zero(), Vec3::Constant(0.1), common::Vec3i(10, 1, 10)};
  cfg.plane_strain_axis = 1;
  cfg.regularisation_length = 0.1;
  cfg.regularisation_modulus = 2e6;
  return cfg;
}

mpm::MaterialPoints band_points(const mpm::Grid& g) {
  mpm::MaterialPoints pts;
  mpm::fill_box(pts, g, Vec3(0.2, 0, 0.2), Vec3(0.8, 0.1, 0.8), common::Vec3i(2, 1, 2), 2000.0, 0);
  // A shear band's velocity field: a jump of v_x across z = 0.5, smoothed over one cell.
  for (std::size_t p = 0; p < pts.size(); ++p) {
    pts.v[p] = Vec3(std::tanh((pts.x[p][2] - 0.5) / 0.1), 0, 0);
  }
  return pts;
}

TEST(GradientRegularisation, TheMaterialKeepsItsOwnLAndTheStateRestartsBitForBit) {
  for (const auto scheme : {mpm::StressUpdate::usf, mpm::StressUpdate::musl}) {
    SCOPED_TRACE(scheme == mpm::StressUpdate::usf ? "usf" : "musl");
    mpm::SolverConfig cfg = band_config();
    cfg.stress_update = scheme;
    RecordingElastic mat_a;
    mpm::Solver a(cfg, band_points(cfg.grid), {&mat_a});
    a.run(3);
    ASSERT_EQ(mat_a.seen.size(), a.points().size());
    for (std::size_t p = 0; p < a.points().size(); ++p)
      EXPECT_TRUE(mat_a.seen[p] == a.points().L[p]);
    common::StateStore store;
    a.save(store);
    mat_a.save(store);
    ASSERT_TRUE(store.has("points/regularisation_strain"));
    a.run(5);

    RecordingElastic mat_b;
    mpm::Solver b(cfg, band_points(cfg.grid), {&mat_b});
    b.load(store);
    mat_b.load(store);
    b.run(5);
    for (std::size_t p = 0; p < a.points().size(); ++p) {
      ASSERT_EQ(a.points().x[p], b.points().x[p]);
      ASSERT_EQ(a.points().v[p], b.points().v[p]);
      ASSERT_EQ(a.points().stress[p], b.points().stress[p]);
    }
    // The regularisation did something: without it the velocities differ.
    mpm::SolverConfig off = cfg;
    off.regularisation_length = off.regularisation_modulus = 0.0;
    RecordingElastic mat_c;
    mpm::Solver c(off, band_points(cfg.grid), {&mat_c});
    c.run(8);
    double differ = 0.0;
    for (std::size_t p = 0; p < a.points().size(); ++p) {
      differ = std::max(differ, (a.points().v[p] - c.points().v[p]).norm());
    }
    EXPECT_GT(differ, 1e-6);
  }
}

TEST(GradientRegularisation, RefusesALengthWithoutModulusAndTheTotalLagrangianFormulation) {
  EXPECT_THROW(mpm::GradientRegularisation(0.01, 0.0, mpm::AverageKind::pairs), common::InputError);
  EXPECT_THROW(mpm::GradientRegularisation(0.0, 1e6, mpm::AverageKind::pairs), common::InputError);
  mpm::SolverConfig cfg = band_config();
  cfg.regularisation_modulus = 0.0;
  EXPECT_THROW(cfg.validate(), common::InputError);
  cfg = band_config();
  cfg.regularisation_length = 0.0;
  EXPECT_THROW(cfg.validate(), common::InputError);
  cfg = band_config();
  cfg.regularisation_length = -0.01;
  EXPECT_THROW(cfg.validate(), common::InputError);
  cfg = band_config();
  cfg.formulation = mpm::Formulation::total_lagrangian;
  cfg.move_points = false;
  EXPECT_THROW(cfg.validate(), common::InputError);
  EXPECT_NO_THROW(band_config().validate());
}

}  // namespace
