// mpm::drucker_prager_return: the cone sqrt(J2) <= eta p, deviatoric or dilatant return, the apex;
// mpm::plane_strain_cone, the match with Mohr-Coulomb in plane strain.
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

// The plane-strain cone: psi = 0 is the deviatoric cone eta = sin(phi), and psi = phi the
// associated match of de Souza Neto, Peric & Owen (2008), eq. 6.121 written with sin(phi):
// eta = 3 tan(phi) / sqrt(9 + 12 tan^2(phi)).
TEST(DruckerPrager, PlaneStrainConeLimits) {
  const double phi = 40.0 * M_PI / 180.0;
  const auto dev = mpm::plane_strain_cone(phi, 0.0);
  EXPECT_EQ(dev.eta, std::sin(phi));
  EXPECT_EQ(dev.eta_bar, 0.0);
  const auto assoc = mpm::plane_strain_cone(phi, phi);
  const double t = std::tan(phi);
  EXPECT_NEAR(assoc.eta, 3.0 * t / std::sqrt(9.0 + 12.0 * t * t), 1e-14);
  EXPECT_NEAR(assoc.eta_bar, assoc.eta, 1e-14);
  const auto mid = mpm::plane_strain_cone(phi, 0.2);  // in between: eta between the two
  EXPECT_LT(mid.eta, dev.eta);
  EXPECT_GT(mid.eta, assoc.eta);
}

// A dilatant return lands on the cone, and the plastic strain it implies, C^-1 (trial - stress),
// points along the potential: its volumetric part is eta_bar times its deviatoric norm sqrt(2) |e|
// (d eps_v = eta_bar dgamma, |d e| = dgamma / sqrt(2)), and its deviator along the trial's.
TEST(DruckerPrager, DilatantReturnFollowsThePotential) {
  Mat3 s;
  s << -2e4, 1e3, 6e3,  //
      1e3, -1e4, -2e3,  //
      6e3, -2e3, -3e3;
  const double bulk = 5e6;
  const double shear = 3e6;
  const mpm::DruckerPragerCone cone{0.5, 0.3};
  const auto r = mpm::drucker_prager_return(s, cone, bulk, shear);
  ASSERT_TRUE(r.plastic);
  EXPECT_FALSE(r.apex);
  const double p = -r.stress.trace() / 3.0;
  EXPECT_GT(p, -s.trace() / 3.0);  // a dilatant flow at a fixed strain raises p
  EXPECT_NEAR(sqrt_j2(r.stress), cone.eta * p, 1e-9 * p);
  const Mat3 dsigma = s - r.stress;
  const double dvol = dsigma.trace() / (3.0 * bulk);  // tension positive
  const Mat3 ddev = (dsigma - dsigma.trace() / 3.0 * Mat3::Identity()) / (2.0 * shear);
  EXPECT_NEAR(dvol, cone.eta_bar * std::sqrt(2.0) * ddev.norm(), 1e-9 * std::abs(dvol));
  const Mat3 dev0 = s - s.trace() / 3.0 * Mat3::Identity();
  EXPECT_LT((ddev / ddev.norm() - dev0 / dev0.norm()).norm(), 1e-9);
}

// With eta_bar = 0 the general return is the deviatoric one, bit for bit.
TEST(DruckerPrager, NoDilatancyIsTheDeviatoricReturn) {
  Mat3 s;
  s << -2e4, 1e3, 6e3,  //
      1e3, -1e4, -2e3,  //
      6e3, -2e3, -3e3;
  const auto a = mpm::drucker_prager_return(s, kSinPhi);
  const auto b = mpm::drucker_prager_return(s, mpm::DruckerPragerCone{kSinPhi, 0.0}, 5e6, 3e6);
  EXPECT_TRUE(a.stress == b.stress);
}

// A slightly tensile trial with a large deviator is not at the apex for a dilatant flow: its
// return raises p above zero (G p + K eta_bar sqrt(J2) > 0); beyond that line it is.
TEST(DruckerPrager, DilatantApexRegion) {
  const double bulk = 5e6;
  const double shear = 3e6;
  const mpm::DruckerPragerCone cone{0.5, 0.3};
  Mat3 s = 1e2 * Mat3::Identity();  // p = -100 Pa
  s(0, 2) = s(2, 0) = 1e4;          // sqrt(J2) = 10 kPa: G p + K eta_bar sqrt(J2) > 0
  const auto r = mpm::drucker_prager_return(s, cone, bulk, shear);
  EXPECT_FALSE(r.apex);
  const double p = -r.stress.trace() / 3.0;
  EXPECT_GT(p, 0.0);
  EXPECT_NEAR(sqrt_j2(r.stress), cone.eta * p, 1e-9 * 1e4);
  Mat3 far = 1e5 * Mat3::Identity();  // p = -100 kPa, same deviator: past the apex
  far(0, 2) = far(2, 0) = 1e4;
  EXPECT_TRUE(mpm::drucker_prager_return(far, cone, bulk, shear).apex);
}
