// dem::Rve: the quasi-static step (eqs. 11-12), guards, stress sign, save/load bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "dem/measures.hpp"
#include "dem/rve.hpp"
#include "dem_test_util.hpp"

namespace {

using common::Mat3;
using common::Vec3;

dem::RveParams params() {
  dem::RveParams p;
  p.material = dem_test::reference_material();
  return p;
}

TEST(Rve, StepAppliesExactIncrementAndReturnsCompressiveStress) {
  dem::Rve rve(dem_test::reference_packing(), params());
  EXPECT_EQ(rve.num_spheres(), 1000u);
  EXPECT_NEAR(rve.d50(), 2e-4, 0.05e-4);
  const Mat3 h0 = rve.simulation().cell().h;
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;          // 1/s
  const double dt = 1e-5;  // increment 1e-5
  const dem::StepReport rep = rve.step(l, dt);
  // T_p = 1e-5 / 2.5e-4 * sqrt(2650 * d50^2 / p) with p ~ 1e5.
  const double expect_tp = 1e-5 / 2.5e-4 * std::sqrt(2650.0 * rve.d50() * rve.d50() / 1e5);
  EXPECT_NEAR(rep.t_p, expect_tp, 0.02 * expect_tp);
  EXPECT_EQ(rep.guards, 0u);
  EXPECT_NEAR(rep.t_p / rep.dem_steps, rep.dt_dem, 1e-20);
  const double lz = rve.simulation().cell().h(2, 2);
  EXPECT_NEAR(lz / h0(2, 2), 1.0 - 1e-5, 1e-10);
  const Mat3 s = rve.stress();
  EXPECT_LT(s.trace(), 0.0);  // compression: tension-positive stress is negative
  EXPECT_NEAR(rep.p, -s.trace() / 3.0, 1e-9 * rep.p);
  EXPECT_LT(s(2, 2), s(0, 0));  // axial compression loads z more
}

// Eq. (11) takes the strain increment: adding a spin to the same strain leaves T_p unchanged, and a
// pure spin has T_p of one DEM step (a rigid rotation is not a deformation); only the strain-split
// guard, which bounds the whole increment (spin included), cuts it into
// ceil(max|W dt| / max_strain_per_step) steps.
TEST(Rve, SpinDoesNotLengthenTheQuasiStaticTime) {
  const dem::Rve base(dem_test::reference_packing(), params());
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;
  Mat3 w = Mat3::Zero();
  w(0, 1) = 3.0;
  w(1, 0) = -3.0;
  dem::Rve a = base;
  dem::Rve b = base;
  dem::Rve c = base;
  const double dt = 1e-5;
  const dem::StepReport ra = a.step(l, dt);
  const dem::StepReport rb = b.step(l + w, dt);
  EXPECT_EQ(rb.t_p, ra.t_p);
  EXPECT_EQ(rb.dem_steps, ra.dem_steps);
  const double dt_dem = c.simulation().numerics().dt_safety * c.simulation().critical_dt();
  const dem::StepReport rc = c.step(w, dt);
  EXPECT_EQ(rc.t_p, dt_dem);
  const auto n_split =
      static_cast<std::int64_t>(std::ceil(3.0 * dt / c.params().max_strain_per_step));
  EXPECT_EQ(rc.dem_steps, std::max<std::int64_t>(n_split, 1));
  EXPECT_EQ((rc.guards & dem::kGuardStrainSplit) != 0, n_split > 1);
}

TEST(Rve, ZeroIncrementAndHugeIncrementAreGuarded) {
  dem::RveParams p = params();
  p.max_strain_per_step = 1e-4;
  p.max_steps_per_call = 4000;
  dem::Rve rve(dem_test::reference_packing(), p);
  const auto r0 = rve.step(Mat3::Zero(), 1e-3);
  EXPECT_TRUE(r0.guards & dem::kGuardZeroIncrement);
  EXPECT_EQ(r0.dem_steps, 1);
  Mat3 l = Mat3::Zero();
  l(0, 0) = 1.0;  // strong extension: 5 % in one call
  const auto r1 = rve.step(l, 0.05);
  EXPECT_TRUE(r1.guards & dem::kGuardStepCap);
  EXPECT_GE(r1.dem_steps, 500);  // at least 0.05 / 1e-4 steps
  EXPECT_TRUE(rve.stress().allFinite());
}

// A step count beyond int64 is capped, not converted (the conversion was undefined: with an
// inertial number of 1e-30, before the job rules refused it, one DEM step of infinite length and
// then "active contact lost"). Reached here with valid parameters: an RVE that has lost its
// contacts, at a pressure floor of 1e-60 Pa, has T_p = emax / I d50 sqrt(rho / 1e-60), about
// 1e26 s, i.e. 1e34 DEM steps.
TEST(Rve, StepCountBeyondInt64IsCapped) {
  dem::RveParams p = params();
  p.p_floor = 1e-60;
  p.max_steps_per_call = 200;
  dem::Rve rve(dem_test::reference_packing(), p);
  for (int k = 0; k < 3; ++k) (void)rve.step(Mat3::Identity(), 0.05);  // lose every contact
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;
  const dem::StepReport r = rve.step(l, 1e-5);
  EXPECT_TRUE(r.guards & dem::kGuardNoContacts);
  EXPECT_TRUE(r.guards & dem::kGuardStepCap);
  EXPECT_EQ(r.dem_steps, 200);
  EXPECT_TRUE(std::isfinite(r.t_p));
  EXPECT_LE(r.t_p, 200.0 * r.dt_dem * (1.0 + 1e-12));
  EXPECT_TRUE(rve.stress().allFinite());
  for (const auto& x : rve.simulation().spheres().x) ASSERT_TRUE(x.allFinite());
}

TEST(Rve, LosingAllContactsGivesZeroStressNoNan) {
  dem::RveParams p = params();
  p.max_steps_per_call = 2000;  // keep the test cheap: the step cap is hit too
  dem::Rve rve(dem_test::reference_packing(), p);
  Mat3 l = Mat3::Identity() * 1.0;  // isotropic extension 10 % : the packing falls apart
  dem::StepReport r;
  for (int k = 0; k < 3; ++k) r = rve.step(l, 0.05);
  EXPECT_TRUE(r.guards & dem::kGuardPressureFloor);
  EXPECT_TRUE(r.guards & dem::kGuardNoContacts);
  EXPECT_TRUE(r.guards & dem::kGuardStepCap);
  EXPECT_EQ(rve.stress().norm(), 0.0);
  EXPECT_TRUE(std::isfinite(r.t_p));
  EXPECT_GT(r.void_ratio, 0.9);
}

TEST(Rve, SaveLoadContinuesBitForBit) {
  dem::Rve a(dem_test::reference_packing(), params());
  Mat3 l = Mat3::Zero();
  l(2, 2) = -2.0;
  l(0, 1) = 1.0;
  a.step(l, 2e-5);
  common::StateStore store;
  a.save(store);
  const auto bytes = store.serialize();
  dem::Rve b = dem::Rve::load(common::StateStore::deserialize(bytes));
  for (int k = 0; k < 2; ++k) {
    const auto ra = a.step(l, 2e-5);
    const auto rb = b.step(l, 2e-5);
    EXPECT_EQ(ra.dem_steps, rb.dem_steps);
  }
  const Mat3 sa = a.stress();
  const Mat3 sb = b.stress();
  EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sizeof(Mat3)), 0);
  const auto& xa = a.simulation().spheres().x;
  const auto& xb = b.simulation().spheres().x;
  EXPECT_EQ(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(Vec3)), 0);
  EXPECT_TRUE(store.has("contacts/shear_force"));
  EXPECT_TRUE(store.has("spheres/x"));
}

TEST(Rve, MissingFieldIsInputError) {
  common::StateStore empty;
  EXPECT_THROW((void)dem::Rve::load(empty), common::InputError);
}

}  // namespace
