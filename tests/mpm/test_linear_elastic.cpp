// Tests of linear_elastic.hpp: uniaxial response, pure spin (objectivity), checkpoint round trip.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "mpm/linear_elastic.hpp"

namespace {

using common::Mat3;

TEST(LinearElastic, SmallStrainIncrementIsHooke) {
  const double E = 2e8, nu = 0.25;
  mpm::LinearElastic m(E, nu, 2000.0);
  std::vector<std::int64_t> ids{0};
  Mat3 L = Mat3::Zero();
  L(0, 0) = 1e-3;  // uniaxial strain rate
  std::vector<Mat3> Ls{L}, s(1);
  m.update_stress(ids, Ls, 1.0, s);
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  // One increment of the rate form is exact: sigma = dt (lambda tr D I + 2 mu D).
  EXPECT_DOUBLE_EQ(s[0](0, 0), (lambda + 2 * mu) * 1e-3);
  EXPECT_DOUBLE_EQ(s[0](1, 1), lambda * 1e-3);
  EXPECT_EQ(s[0](0, 1), 0.0);
  EXPECT_NEAR(m.wave_speed(), std::sqrt((lambda + 2 * mu) / 2000.0), 1e-12);
}

TEST(LinearElastic, PureSpinRotatesStressKeepingInvariants) {
  Mat3 s0;
  s0 << -100e3, 20e3, 0, 20e3, -50e3, 5e3, 0, 5e3, -80e3;
  mpm::LinearElastic m(1e8, 0.3, 1000.0, s0);
  const double omega = 2.0, dt = 1e-3;
  Mat3 W = Mat3::Zero();
  W(0, 1) = -omega;
  W(1, 0) = omega;  // spin about z
  std::vector<std::int64_t> ids{7};
  std::vector<Mat3> Ls{W}, s(1);
  const int n = 785;  // about a quarter turn
  for (int k = 0; k < n; ++k) m.update_stress(ids, Ls, dt, s);
  // Hughes-Winget rotates by 2 atan(omega dt / 2) per step, exactly orthogonally.
  const double angle = n * 2.0 * std::atan(0.5 * omega * dt);
  const Mat3 R = Eigen::AngleAxisd(angle, common::Vec3::UnitZ()).toRotationMatrix();
  const Mat3 expected = R * s0 * R.transpose();
  // Round-off of 785 products of orthogonal matrices: ~1e-13 relative; 1e-9 Pa of 1e5 Pa.
  EXPECT_LT((s[0] - expected).cwiseAbs().maxCoeff(), 1e-9 * 1e5);
  // And the angle is the true one, omega t, to O(n (omega dt)^3 / 12) = 5e-7 rad.
  EXPECT_NEAR(angle, omega * dt * n, 1e-6);
}

TEST(LinearElastic, RejectsBadParameters) {
  EXPECT_THROW(mpm::LinearElastic(-1.0, 0.3, 1.0), common::InputError);
  EXPECT_THROW(mpm::LinearElastic(1.0, 0.5, 1.0), common::InputError);
  EXPECT_THROW(mpm::LinearElastic(1.0, 0.3, 0.0), common::InputError);
}

TEST(LinearElastic, StateRoundTrip) {
  mpm::LinearElastic a(1e6, 0.2, 1.0);
  Mat3 s = Mat3::Random();
  a.set_stress(3, s);
  common::StateStore store;
  a.save(store, "material/0/");
  mpm::LinearElastic b(1e6, 0.2, 1.0);
  b.load(store, "material/0/");
  EXPECT_EQ(b.stress(3), s);
  EXPECT_EQ(b.stress(0), Mat3::Zero());
  // A stress that is not finite is refused naming the field and the value.
  common::StateStore bad;
  std::vector<double> flat = store.read_f64("material/0/stress");
  flat[30] = std::nan("");
  bad.write("material/0/stress", flat);
  try {
    b.load(bad, "material/0/");
    ADD_FAILURE() << "loaded a NaN stress";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material/0/stress: value 30 is nan"), std::string::npos)
        << e.what();
  }
}

}  // namespace
