// dem::Rve: the quasi-static step (eqs. 11-12), guards, stress sign, save/load bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "dem/measures.hpp"
#include "dem/rve.hpp"
#include "dem_test_util.hpp"
#include "former_state.hpp"

namespace {

using common::Mat3;
using common::Vec3;

// The paper's step (eq. 11 at every rate, a cell strained without contacts): what these tests
// check; the material rate and the disconnected state are tested in test_rve_rate.cpp.
dem::RveParams params() {
  dem::RveParams p;
  p.material = dem_test::reference_material();
  p.rate = dem::RveRate::coupling;
  p.contact_loss = dem::ContactLoss::strained;
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

// StepReport::rebuilds counts the neighbour-list builds of the step's DEM steps (the farm's cost
// traces read it): none for a tiny increment, at least one when the strain outruns the skin, and
// always the list's own counter's growth.
TEST(Rve, StepReportsItsNeighbourListBuilds) {
  dem::Rve rve(dem_test::reference_packing(), params());
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;
  std::int64_t builds = rve.simulation().verlet().builds;
  const dem::StepReport tiny = rve.step(l, 1e-7);
  EXPECT_EQ(tiny.rebuilds, 0U);
  EXPECT_EQ(rve.simulation().verlet().builds, builds);
  std::uint32_t total = 0;
  for (int k = 0; k < 20; ++k) {
    builds = rve.simulation().verlet().builds;
    const dem::StepReport big = rve.step(l, 2e-4);  // 0.4 % of the cell, 20 times: 4 %
    EXPECT_EQ(static_cast<std::int64_t>(big.rebuilds), rve.simulation().verlet().builds - builds);
    total += big.rebuilds;
  }
  EXPECT_GE(total, 1U);
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

// The same bits: stress and sphere positions.
void expect_same_stress_and_positions(const dem::Rve& a, const dem::Rve& b) {
  const Mat3 sa = a.stress();
  const Mat3 sb = b.stress();
  EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sizeof(Mat3)), 0);
  const auto& xa = a.simulation().spheres().x;
  const auto& xb = b.simulation().spheres().x;
  ASSERT_EQ(xa.size(), xb.size());
  EXPECT_EQ(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(Vec3)), 0);
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
  expect_same_stress_and_positions(a, b);
  EXPECT_TRUE(store.has("contacts/shear_force"));
  EXPECT_TRUE(store.has("spheres/x"));
}

// dem.coupling.dt_refresh (docs/design/dem.md "RVE step"): the critical time step of an RVE step is
// the one computed at its start (default: every step, the results of before the key), or kept
// while fewer than dt_refresh DEM steps have run since it was computed and the contacts have not
// grown by more than 5 %.
std::int64_t active_contacts(const dem::Rve& rve) {
  std::int64_t nc = 0;
  for (auto a : rve.simulation().contacts().active) nc += a;
  return nc;
}

TEST(Rve, CriticalDtIsComputedAtEveryStepByDefault) {
  dem::Rve rve(dem_test::reference_packing(), params());
  ASSERT_EQ(rve.params().dt_refresh, 1);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;
  l(0, 1) = 0.5;
  for (int k = 0; k < 4; ++k) {
    const double fresh = rve.simulation().critical_dt();
    const dem::StepReport r = rve.step(l, 1e-6);
    EXPECT_EQ(rve.dt_cache().critical_dt, fresh) << "step " << k;
    EXPECT_EQ(rve.dt_cache().dem_steps, r.dem_steps);
    EXPECT_LE(r.dt_dem, rve.simulation().numerics().dt_safety * fresh);
  }
}

// Zero increments: one relaxation DEM step per RVE step, which moves the spheres a little (the
// critical time step changes in its last bits) and creates no contacts.
TEST(Rve, CriticalDtIsKeptForDtRefreshDemSteps) {
  dem::RveParams p = params();
  p.dt_refresh = 10;
  dem::Rve rve(dem_test::reference_packing(), p);
  double kept = 0.0;
  int stale = 0;  // steps that ran with a value other than a fresh computation's
  for (int k = 0; k < 25; ++k) {
    const double fresh = rve.simulation().critical_dt();
    const dem::StepReport r = rve.step(Mat3::Zero(), 1e-9);
    ASSERT_EQ(r.dem_steps, 1);
    if (k % 10 == 0) {  // computed at steps 0, 10, 20
      EXPECT_EQ(rve.dt_cache().critical_dt, fresh) << "step " << k;
      EXPECT_EQ(rve.dt_cache().dem_steps, 1);
      kept = fresh;
    } else {
      EXPECT_EQ(rve.dt_cache().critical_dt, kept) << "step " << k;
      EXPECT_EQ(rve.dt_cache().dem_steps, k % 10 + 1);
      stale += fresh != kept ? 1 : 0;
    }
    EXPECT_EQ(r.t_p, rve.simulation().numerics().dt_safety * kept);
  }
  EXPECT_GT(stale, 0);  // the test can tell a kept value from a computed one
}

// Compression creates contacts: the kept value is computed anew as soon as the contacts at the
// start of a step are more than 5 % above those it was computed for, whatever dt_refresh says.
TEST(Rve, CriticalDtIsComputedAnewWhenContactsGrow) {
  dem::RveParams p = params();
  p.dt_refresh = 1'000'000;
  p.max_strain_per_step = 1e-4;
  p.inertial_number = 0.1;  // fast compression: a few tens of DEM steps per RVE step
  dem::Rve rve(dem_test::reference_packing(), p);
  (void)rve.step(Mat3::Zero(), 1e-9);
  const Mat3 l = -Mat3::Identity();  // isotropic compression, 0.2 % per RVE step
  int grown = 0;
  int kept = 0;
  for (int k = 0; k < 8; ++k) {
    const double before = rve.dt_cache().critical_dt;
    const std::int64_t ref = rve.dt_cache().contacts;
    const std::int64_t nc = active_contacts(rve);
    const double fresh = rve.simulation().critical_dt();
    (void)rve.step(l, 2e-3);
    if (20 * nc > 21 * ref) {
      ++grown;
      EXPECT_EQ(rve.dt_cache().critical_dt, fresh) << "step " << k;
      EXPECT_EQ(rve.dt_cache().contacts, nc);
    } else {
      ++kept;
      EXPECT_EQ(rve.dt_cache().critical_dt, before) << "step " << k;
    }
  }
  EXPECT_GT(grown, 0);
  EXPECT_GT(kept, 0);
}

dem::Rve stepped_with_kept_dt(int steps) {
  dem::RveParams p = params();
  p.dt_refresh = 7;
  dem::Rve rve(dem_test::reference_packing(), p);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1e-3;
  for (int k = 0; k < steps; ++k) (void)rve.step(l, 1e-6);
  return rve;
}

// A state saved between two computations continues bit for bit: the kept value and its counts
// are part of it. A state written before they were (no rve/dt_* fields) loads as dt_refresh = 1.
TEST(Rve, SaveLoadWithKeptCriticalDtContinuesBitForBit) {
  dem::Rve a = stepped_with_kept_dt(3);
  ASSERT_GT(a.dt_cache().dem_steps, 0);
  ASSERT_LT(a.dt_cache().dem_steps, 7);
  common::StateStore store;
  a.save(store);
  dem::Rve b = dem::Rve::load(common::StateStore::deserialize(store.serialize()));
  EXPECT_EQ(b.params().dt_refresh, 7);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1e-3;
  for (int k = 0; k < 12; ++k) {
    const auto ra = a.step(l, 1e-6);
    const auto rb = b.step(l, 1e-6);
    ASSERT_EQ(ra.dem_steps, rb.dem_steps);
    ASSERT_EQ(ra.t_p, rb.t_p);
  }
  EXPECT_EQ(std::memcmp(&a.dt_cache(), &b.dt_cache(), sizeof(dem::Rve::DtCache)), 0);
  const auto& xa = a.simulation().spheres().x;
  const auto& xb = b.simulation().spheres().x;
  EXPECT_EQ(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(Vec3)), 0);

  // A state of before (DEM state version 3, without rve/dt_refresh and rve/dt_cache/*).
  const dem::Rve c =
      dem::Rve::load(dem_test::copy_without(dem_test::as_former_version(store, 3), "rve/dt_"));
  EXPECT_EQ(c.params().dt_refresh, 1);
  EXPECT_EQ(c.dt_cache().critical_dt, 0.0);

  // A cached value that cannot be: refused, naming the fields.
  common::StateStore bad = dem_test::copy_without(store, "rve/dt_cache/critical_dt");
  bad.write("rve/dt_cache/critical_dt", std::span<const double>(std::vector<double>{-1.0}));
  try {
    (void)dem::Rve::load(bad);
    ADD_FAILURE() << "a negative cached critical time step was accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rve/dt_cache"), std::string::npos) << e.what();
  }
  // A contact count beyond the state's pairs (its growth test multiplies it): refused too.
  common::StateStore many = dem_test::copy_without(store, "rve/dt_cache/contacts");
  many.write("rve/dt_cache/contacts", std::span<const std::int64_t>(std::vector<std::int64_t>{
                                          std::numeric_limits<std::int64_t>::max()}));
  EXPECT_THROW((void)dem::Rve::load(many), common::InputError);
}

// dem.coupling.end_forces = "carried" (docs/design/dem.md "RVE step"): the end state's forces are
// computed with the step's dt and L and drive the next step's first DEM step. The same motion as
// "separate" but for the contacts' increments at the steps' ends (the last DEM step's shear,
// rolling and twisting increments counted with its own dt instead of the next step's): the
// stresses agree to a small fraction of p, and the work differs by one force evaluation per step.
TEST(Rve, CarriedEndForcesGiveTheSeparateEvaluationsStress) {
  dem::RveParams p = params();
  p.carry_end_forces = false;  // "separate" (the default is "carried")
  dem::Rve separate(dem_test::reference_packing(), p);
  p.carry_end_forces = true;
  dem::Rve carried = dem::Rve::from_simulation(separate.simulation(), p);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;
  l(0, 1) = 0.5;
  double largest = 0.0;
  for (int k = 0; k < 6; ++k) {
    const double dt = k % 2 == 0 ? 2e-6 : 3e-7;  // the DEM step changes between RVE steps
    const dem::StepReport a = separate.step(l, dt);
    const dem::StepReport b = carried.step(l, dt);
    ASSERT_EQ(a.dem_steps, b.dem_steps) << "step " << k;
    largest = std::max(largest, (separate.stress() - carried.stress()).cwiseAbs().maxCoeff() / a.p);
  }
  EXPECT_GT(largest, 0.0);   // other bits
  EXPECT_LT(largest, 1e-3);  // the same state
  const auto& xa = separate.simulation().spheres().x;
  const auto& xb = carried.simulation().spheres().x;
  double dx = 0.0;
  for (std::size_t i = 0; i < xa.size(); ++i) dx = std::max(dx, (xa[i] - xb[i]).norm());
  // The spheres move alike: the modes differ in T_p (through the end stress's p) and in the
  // increments at the steps' ends: 1.1 % of the cell's affine displacement (|h| times the strain)
  // here, the bound 5 %.
  const double affine = (3 * 2e-6 + 3 * 3e-7) * separate.simulation().cell().h.norm();
  EXPECT_LT(dx, 0.05 * affine);
}

TEST(Rve, CarriedEndForcesContinueBitForBitAfterSaveLoad) {
  dem::RveParams p = params();
  p.carry_end_forces = true;
  dem::Rve a(dem_test::reference_packing(), p);
  Mat3 l = Mat3::Zero();
  l(2, 2) = -1.0;
  (void)a.step(l, 1e-6);
  common::StateStore store;
  a.save(store);
  EXPECT_EQ(store.read_i64("rve/forces_carried"), std::vector<std::int64_t>{1});
  dem::Rve b = dem::Rve::load(common::StateStore::deserialize(store.serialize()));
  EXPECT_TRUE(b.params().carry_end_forces);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(a.step(l, 1e-6).dem_steps, b.step(l, 1e-6).dem_steps);
  }
  expect_same_stress_and_positions(a, b);
  // Carried forces in a state that does not carry them cannot be: refused, naming the fields.
  common::StateStore bad = dem_test::copy_without(store, "rve/params/end_forces");
  bad.write("rve/params/end_forces", std::span<const std::int64_t>(std::vector<std::int64_t>{0}));
  try {
    (void)dem::Rve::load(bad);
    ADD_FAILURE() << "carried forces without carry_end_forces were accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rve/forces_carried"), std::string::npos) << e.what();
  }
  // A state of before the key (DEM state version 3, without rve/carry_end_forces) loads as
  // "separate".
  const dem::Rve old = dem::Rve::load(dem_test::copy_without(
      dem_test::copy_without(dem_test::as_former_version(store, 3), "rve/carry_end_forces"),
      "rve/forces_"));
  EXPECT_FALSE(old.params().carry_end_forces);
}

TEST(Rve, MissingFieldIsInputError) {
  common::StateStore empty;
  EXPECT_THROW((void)dem::Rve::load(empty), common::InputError);
}

}  // namespace
