// mpm::drucker_prager_return: the cone sqrt(J2) <= p sin(phi), deviatoric return, apex at p <= 0.
#include <gtest/gtest.h>

#include <cmath>

#include "common/types.hpp"
#include "mpm/drucker_prager.hpp"

namespace {

using common::Mat3;

double sqrt_j2(const Mat3& s) {
  const Mat3 dev = s - s.trace() / 3.0 * Mat3::Identity();
  return std::sqrt(0.5 * (dev.array() * dev.array()).sum());
}

const double kSinPhi = std::sin(30.0 * M_PI / 180.0);

}  // namespace

// A stress inside the cone comes back unchanged, bit for bit.
TEST(DruckerPrager, InsideTheConeIsElastic) {
  Mat3 s = -1e4 * Mat3::Identity();
  s(0, 2) = s(2, 0) = 3e3;  // sqrt(J2) = 3 kPa < p sin(30 deg) = 5 kPa
  const auto r = mpm::drucker_prager_return(s, kSinPhi);
  EXPECT_FALSE(r.plastic);
  EXPECT_TRUE(r.stress == s);
}

// A stress outside is returned onto the cone along its deviator: p kept, the deviator's direction
// kept, sqrt(J2) = p sin(phi).
TEST(DruckerPrager, OutsideReturnsRadiallyOntoTheCone) {
  Mat3 s;
  s << -2e4, 1e3, 6e3,  //
      1e3, -1e4, -2e3,  //
      6e3, -2e3, -3e3;
  const double p = -s.trace() / 3.0;
  ASSERT_GT(sqrt_j2(s), p * kSinPhi);
  const auto r = mpm::drucker_prager_return(s, kSinPhi);
  EXPECT_TRUE(r.plastic);
  EXPECT_FALSE(r.apex);
  EXPECT_NEAR(-r.stress.trace() / 3.0, p, 1e-9 * p);
  EXPECT_NEAR(sqrt_j2(r.stress), p * kSinPhi, 1e-9 * p);
  const Mat3 dev0 = s + p * Mat3::Identity();
  const Mat3 dev1 = r.stress + p * Mat3::Identity();
  const double k = dev1(0, 2) / dev0(0, 2);
  EXPECT_LT(k, 1.0);
  EXPECT_LT((dev1 - k * dev0).norm(), 1e-9 * dev0.norm());    // same direction
  EXPECT_TRUE(r.stress.isApprox(r.stress.transpose(), 0.0));  // stays symmetric
}

// Plane strain, no dilatancy: at yield s_yy = 0, and the cone is Mohr-Coulomb's
// (sigma_1 - sigma_3) / (sigma_1 + sigma_3) = sin(phi) (the match the header states).
TEST(DruckerPrager, MatchesMohrCoulombInPlaneStrain) {
  const double s1 = -3e4;
  const double s3 = s1 * (1.0 - kSinPhi) / (1.0 + kSinPhi);  // on the Mohr-Coulomb line
  Mat3 s = Mat3::Zero();
  s(0, 0) = s3;
  s(2, 2) = s1;
  s(1, 1) = 0.5 * (s1 + s3);  // s_yy = 0
  const auto r = mpm::drucker_prager_return(s, kSinPhi);
  EXPECT_NEAR(sqrt_j2(s), -s.trace() / 3.0 * kSinPhi, 1e-9 * std::abs(s1));
  EXPECT_TRUE(r.stress.isApprox(s, 1e-12));
}

// A tensile mean stress returns to the apex: a cohesionless material carries no stress.
TEST(DruckerPrager, TensionReturnsToZeroStress) {
  Mat3 s = 1e3 * Mat3::Identity();
  s(0, 1) = s(1, 0) = -5e2;
  const auto r = mpm::drucker_prager_return(s, kSinPhi);
  EXPECT_TRUE(r.apex);
  EXPECT_TRUE(r.stress == Mat3::Zero());
  EXPECT_TRUE(mpm::drucker_prager_return(Mat3::Zero(), kSinPhi).apex);
}
