// mpm::softening_return: the Drucker-Prager cone whose friction falls with the plastic shear
// strain; checked against the closed-form simple-shear curve of a linear elastic, linearly
// softening material, and against the perfectly plastic return it reduces to.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/types.hpp"
#include "mpm/drucker_prager.hpp"
#include "mpm/friction_softening.hpp"

namespace {

using common::Mat3;

const double kPeak = std::sin(40.0 * M_PI / 180.0);
const double kResidual = std::sin(30.0 * M_PI / 180.0);
constexpr double kShear = 5e6;  // G [Pa]
constexpr double kP = 1e5;      // p [Pa]

mpm::FrictionSoftening softening(double strain) { return {kPeak, kResidual, strain}; }

// Simple shear (x along z) at constant p by an engineering shear strain increment d: the elastic
// predictor adds G d to tau (small strain, no rotation: the return alone is checked).
Mat3 sheared(const Mat3& stress, double d) {
  Mat3 trial = stress;
  trial(0, 2) += kShear * d;
  trial(2, 0) += kShear * d;
  return trial;
}

}  // namespace

// With the residual equal to the peak the return is the perfectly plastic one, bit for bit.
TEST(FrictionSoftening, WithoutSofteningIsThePerfectlyPlasticReturn) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const mpm::FrictionSoftening none{kPeak, kPeak, 0.01};
  for (int k = 0; k < 200; ++k) {
    Mat3 s;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) s(i, j) = s(j, i) = 1e5 * u(rng);
    }
    s -= 1e5 * Mat3::Identity();
    const auto a = mpm::softening_return(s, none, 0.02 * (1.0 + u(rng)), kShear);
    const auto b = mpm::drucker_prager_return(s, kPeak);
    EXPECT_TRUE(a.result.stress == b.stress) << k;
    EXPECT_EQ(a.result.plastic, b.plastic);
    EXPECT_EQ(a.result.apex, b.apex);
  }
}

// Simple shear through the peak: tau = G gamma up to the peak p sin(phi_p); on the softening
// branch tau = p (eta_p - k gamma) / (1 - k p / G) (tau = eta(gamma_p) p with gamma_p = gamma -
// tau / G); past the residual strain tau = p sin(phi_r). The implicit return follows the curve
// to rounding at every increment, large or small.
TEST(FrictionSoftening, SimpleShearFollowsTheClosedFormCurve) {
  const double strain = 0.05;
  const auto soft = softening(strain);
  const double k = (kPeak - kResidual) / strain;
  for (const double d : {1e-4, 1.7e-3}) {
    Mat3 stress = -kP * Mat3::Identity();
    double gamma_p = 0.0;
    double gamma = 0.0;
    for (int n = 0; gamma < 0.2; ++n) {
      const auto r = mpm::softening_return(sheared(stress, d), soft, gamma_p, kShear);
      stress = r.result.stress;
      gamma_p = r.gamma;
      gamma += d;
      double tau = kShear * gamma;
      if (tau > kPeak * kP) {
        tau = std::max(kP * (kPeak - k * gamma) / (1.0 - k * kP / kShear), kResidual * kP);
      }
      SCOPED_TRACE(testing::Message() << "d " << d << " gamma " << gamma);
      EXPECT_NEAR(stress(0, 2), tau, 1e-9 * kP);
      EXPECT_NEAR(-stress.trace() / 3.0, kP, 1e-9 * kP);
      EXPECT_NEAR(gamma_p, gamma - stress(0, 2) / kShear, 1e-12);  // the plastic part of gamma
    }
    EXPECT_NEAR(stress(0, 2), kResidual * kP, 1e-9 * kP);
  }
}

// A step that passes the residual strain returns onto the residual cone, and the plastic strain
// it reports is the whole plastic part of the step.
TEST(FrictionSoftening, AStepPastTheResidualStrainEndsOnTheResidualCone) {
  const auto soft = softening(0.01);
  Mat3 stress = -kP * Mat3::Identity();
  stress(0, 2) = stress(2, 0) = kPeak * kP;  // on the peak cone, gamma_p = 0
  const Mat3 trial = sheared(stress, 0.05);
  const auto r = mpm::softening_return(trial, soft, 0.0, kShear);
  EXPECT_NEAR(r.result.stress(0, 2), kResidual * kP, 1e-9 * kP);
  EXPECT_NEAR(r.gamma, (trial(0, 2) - kResidual * kP) / kShear, 1e-12);
  EXPECT_GT(r.gamma, soft.strain);
}

// Softening faster than the elastic unloading (G <= k p): no stress on the softening branch is
// consistent; the point drops to the residual cone and its gamma to at least the residual strain.
TEST(FrictionSoftening, ASnapBackDropsToTheResidualCone) {
  const double strain = (kPeak - kResidual) * kP / kShear * 0.5;  // k p = 2 G
  const auto soft = softening(strain);
  Mat3 stress = -kP * Mat3::Identity();
  stress(0, 2) = stress(2, 0) = kPeak * kP;
  const auto r = mpm::softening_return(sheared(stress, 1e-7), soft, 0.0, kShear);
  EXPECT_NEAR(r.result.stress(0, 2), kResidual * kP, 1e-9 * kP);
  EXPECT_GE(r.gamma, strain);
}

// Tension returns to zero stress; the plastic strain is kept.
TEST(FrictionSoftening, TensionReturnsToTheApex) {
  const auto r = mpm::softening_return(1e3 * Mat3::Identity(), softening(0.05), 0.02, kShear);
  EXPECT_TRUE(r.result.apex);
  EXPECT_TRUE(r.result.stress == Mat3::Zero());
  EXPECT_EQ(r.gamma, 0.02);
}
