// Unit tests of the ElasticMicro verification model (farm/elastic_micro.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "farm/elastic_micro.hpp"

namespace {

farm::ElasticMicroParams params() {
  farm::ElasticMicroParams p;
  p.young = 10e6;
  p.poisson = 0.2;
  p.density = 2000.0;
  p.initial_stress = -1e5 * common::Mat3::Identity();
  p.initial_stress(0, 1) = p.initial_stress(1, 0) = 2e4;
  return p;
}

}  // namespace

// A pure spin rotates the stress (objectivity): invariants unchanged, rotated by Q.
TEST(ElasticMicro, SpinRotatesStressKeepingInvariants) {
  farm::ElasticMicro m(1, params());
  common::Mat3 W = common::Mat3::Zero();
  W(0, 1) = -0.3;
  W(1, 0) = 0.3;
  const common::Mat3 s0 = m.stress();
  const farm::MicroReport r0 = m.step(common::Mat3::Zero(), 1e-3);
  for (int k = 0; k < 100; ++k) m.step(W, 1e-2);
  const common::Mat3 s = m.stress();
  EXPECT_NEAR(s.trace(), s0.trace(), 1e-9 * std::abs(s0.trace()));
  EXPECT_NEAR(s.norm(), s0.norm(), 1e-9 * s0.norm());
  EXPECT_GT((s - s0).norm(), 1e3);  // it did rotate
  EXPECT_NEAR(r0.p, 1e5, 1e-6);
}

TEST(ElasticMicro, UniaxialStrainFollowsHooke) {
  farm::ElasticMicroParams p = params();
  p.initial_stress = common::Mat3::Zero();
  p.substeps = 4;
  farm::ElasticMicro m(2, p);
  common::Mat3 L = common::Mat3::Zero();
  L(2, 2) = -1.0;
  m.step(L, 1e-4);
  const double lambda = p.young * p.poisson / ((1 + p.poisson) * (1 - 2 * p.poisson));
  const double mu = p.young / (2 * (1 + p.poisson));
  EXPECT_NEAR(m.stress()(2, 2), -(lambda + 2 * mu) * 1e-4, 1e-9 * (lambda + 2 * mu));
  EXPECT_NEAR(m.stress()(0, 0), -lambda * 1e-4, 1e-9 * lambda);
}

TEST(ElasticMicro, SaveLoadContinuesBitForBit) {
  farm::ElasticMicro a(5, params());
  common::Mat3 L;
  L << 0.1, 0.2, 0.0, -0.1, 0.05, 0.3, 0.0, 0.01, -0.2;
  a.step(L, 1e-3);
  common::StateStore s;
  a.save(s);
  const auto bytes = s.serialize();
  auto b = farm::ElasticMicro::load(common::StateStore::deserialize(bytes));
  a.step(L, 1e-3);
  b->step(L, 1e-3);
  EXPECT_EQ(std::memcmp(a.stress().data(), b->stress().data(), 9 * sizeof(double)), 0);
}

TEST(ElasticMicro, InjectedFailureAndBadParams) {
  farm::ElasticMicroParams p = params();
  p.fail_id = 3;
  p.fail_step = 2;
  farm::ElasticMicro m(3, p);
  m.step(common::Mat3::Zero(), 1e-3);
  EXPECT_THROW(m.step(common::Mat3::Zero(), 1e-3), common::NumericalError);
  p.young = -1;
  EXPECT_THROW(farm::ElasticMicro(1, p), common::InputError);
}

TEST(ElasticMicro, LoadRefusesMissingField) {
  common::StateStore s;
  s.write("elastic/id", std::vector<std::int64_t>{1});
  EXPECT_THROW(farm::ElasticMicro::load(s), common::InputError);
}
