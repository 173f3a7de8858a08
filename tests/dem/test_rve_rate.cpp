// dem::Rve's rate (RveRate: the RVE at the material's own inertial number where it flows faster
// than the coupling one) and its contact loss (ContactLoss: a disconnected, stress-free material
// that takes dilation as free volume and reconnects when compressed back).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "dem/element_test.hpp"
#include "dem/rve.hpp"
#include "dem_test_util.hpp"
#include "former_state.hpp"

namespace {

using common::Mat3;

dem::RveParams params(dem::RveRate rate, dem::ContactLoss loss) {
  dem::RveParams p;
  p.material = dem_test::reference_material();
  p.inertial_number = 1e-2;
  p.rate = rate;
  p.contact_loss = loss;
  p.max_strain_per_step = 1e-2;  // the physics bounds the DEM step here; the guard would split it
  return p;
}

Mat3 simple_shear(double gdot) {
  Mat3 l = Mat3::Zero();
  l(0, 2) = gdot;
  return l;
}

bool same_bits(const Mat3& a, const Mat3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Mat3)) == 0;
}

// Slower than the coupling inertial number, both rates run the same quasi-static step, bit for bit.
// Faster, `material` runs the increment over the MPM step itself (the RVE's I is the material's),
// `coupling` over T_p of eq. (11), which is then longer than the step.
TEST(RveRate, MaterialRateRunsInPhysicalTimeOnlyWhereTheMaterialIsFaster) {
  const dem::Packing pk = dem_test::reference_packing();
  dem::Rve slow_c(pk, params(dem::RveRate::coupling, dem::ContactLoss::disconnected));
  dem::Rve slow_m(pk, params(dem::RveRate::material, dem::ContactLoss::disconnected));
  const double t_i = dem::inertial_time(slow_m.d50(), 2650.0, 1e5);  // p ~ 100 kPa
  const double dt = 1e-5;
  // Material at I = 1e-3 (< I_n = 1e-2): |D| = I / t_i, D of simple shear = gdot / 2.
  const Mat3 l_slow = simple_shear(2.0 * 1e-3 / t_i);
  for (int k = 0; k < 3; ++k) {
    const dem::StepReport a = slow_c.step(l_slow, dt);
    const dem::StepReport b = slow_m.step(l_slow, dt);
    EXPECT_EQ(a.dem_steps, b.dem_steps);
    EXPECT_EQ(a.t_p, b.t_p);
    EXPECT_LT(b.t_p, dt);
    EXPECT_EQ(b.guards & dem::kGuardMaterialRate, 0u);
    EXPECT_TRUE(same_bits(slow_c.stress(), slow_m.stress()));
  }
  // Material at I = 0.2 (20 I_n): T_p of eq. (11) is ~20 dt; the material rate runs dt.
  dem::Rve fast_c(pk, params(dem::RveRate::coupling, dem::ContactLoss::disconnected));
  dem::Rve fast_m(pk, params(dem::RveRate::material, dem::ContactLoss::disconnected));
  const Mat3 l_fast = simple_shear(2.0 * 0.2 / t_i);
  const double dt_fast = 2e-7;  // an increment of 2.5e-3: T_p(eq. 11) ~ 4e-6 s
  const dem::StepReport a = fast_c.step(l_fast, dt_fast);
  const dem::StepReport b = fast_m.step(l_fast, dt_fast);
  EXPECT_GT(a.t_p, 10.0 * dt_fast);
  EXPECT_EQ(a.guards & dem::kGuardMaterialRate, 0u);
  EXPECT_EQ(b.t_p, dt_fast);
  EXPECT_NE(b.guards & dem::kGuardMaterialRate, 0u);
  EXPECT_LT(b.dem_steps, a.dem_steps);
  EXPECT_NEAR(b.t_p / static_cast<double>(b.dem_steps), b.dt_dem, 1e-20);
  // The same increment either way: the cells end equal.
  EXPECT_TRUE(fast_c.simulation().cell().h.isApprox(fast_m.simulation().cell().h, 1e-12));
}

// A step shorter than one DEM step runs one DEM step of that length (physical time), never a
// longer one.
TEST(RveRate, StepShorterThanADemStepRunsOneShorterDemStep) {
  dem::Rve rve(dem_test::reference_packing(),
               params(dem::RveRate::material, dem::ContactLoss::disconnected));
  const double dt_dem = rve.simulation().numerics().dt_safety * rve.simulation().critical_dt();
  const double dt = 0.25 * dt_dem;
  const dem::StepReport r = rve.step(simple_shear(1e3), dt);
  EXPECT_EQ(r.dem_steps, 1);
  EXPECT_EQ(r.t_p, dt);
  EXPECT_EQ(r.dt_dem, dt);
}

double solid_fraction(const dem::Rve& rve) { return 1.0 / (1.0 + rve.measure().void_ratio); }

// Extended in steps of 0.6 % volume until it has no contact and a solid fraction below 0.5 (the
// default disconnect_fraction): from then on a dilation is held with "disconnected".
dem::Rve without_contacts(dem::ContactLoss loss) {
  dem::Rve rve(dem_test::reference_packing(), params(dem::RveRate::material, loss));
  dem::StepReport r;
  for (int k = 0; k < 80 && ((r.guards & dem::kGuardNoContacts) == 0 ||
                             !(solid_fraction(rve) < rve.params().disconnect_fraction));
       ++k) {
    r = rve.step(Mat3::Identity() * 1e3, 2e-6);  // a few DEM steps each
    EXPECT_EQ(r.guards & dem::kGuardDisconnected, 0u) << "held above the fraction, step " << k;
  }
  EXPECT_NE(r.guards & dem::kGuardNoContacts, 0u) << "the packing did not come apart";
  EXPECT_LT(solid_fraction(rve), rve.params().disconnect_fraction);
  EXPECT_EQ(rve.free_volume(), 0.0);
  return rve;
}

// Above the disconnection fraction a contact-free RVE is a dense gas, not held: an isochoric
// shear (no compression at all) makes contacts again and it carries a stress.
TEST(ContactLoss, ContactFreeDenseRveIsNotHeldAndAShearReconnectsIt) {
  dem::Rve rve(dem_test::reference_packing(),
               params(dem::RveRate::material, dem::ContactLoss::disconnected));
  dem::StepReport r;
  for (int k = 0; k < 100 && (r.guards & dem::kGuardNoContacts) == 0; ++k) {
    r = rve.step(Mat3::Identity() * 1e2, 2e-6);  // 0.06 % volume each
  }
  ASSERT_NE(r.guards & dem::kGuardNoContacts, 0u);
  EXPECT_GT(solid_fraction(rve), 0.58);
  std::printf("contact-free at solid fraction %.4f\n", solid_fraction(rve));
  r = rve.step(Mat3::Identity() * 1e2, 2e-6);  // one more dilation: not held
  EXPECT_EQ(r.guards & dem::kGuardDisconnected, 0u);
  EXPECT_GT(r.dem_steps, 0);
  double p = 0.0;
  for (int k = 0; k < 100 && !(p > 1e3); ++k) p = rve.step(simple_shear(1e3), 2e-6).p;
  EXPECT_GT(p, 1e3);
  EXPECT_EQ(rve.free_volume(), 0.0);
}

// Disconnected: the dilation of a contact-free RVE goes to its free volume, the cell is held and
// the stress is exactly zero; a compression closes the free volume first (the cell does not
// move), then strains the cell by the remainder only; compressed further, the RVE reconnects and
// carries a pressure again. `strained` stretches the cell instead (the results of before).
TEST(ContactLoss, DisconnectedRveHoldsItsCellAndReconnectsWhenCompressedBack) {
  dem::Rve rve = without_contacts(dem::ContactLoss::disconnected);
  const Mat3 h_lost = rve.simulation().cell().h;
  const double t_lost = rve.simulation().time();
  // Steps of 1e-6 s: the compression that reconnects the RVE runs a few DEM steps each.
  constexpr double kDt = 1e-6;
  const Mat3 l = Mat3::Identity() * 1e4;  // + 3 % volume per step
  for (int k = 0; k < 40; ++k) {          // the material's volume grows 3.3 times
    const dem::StepReport r = rve.step(l, kDt);
    ASSERT_NE(r.guards & dem::kGuardDisconnected, 0u) << "step " << k;
    EXPECT_EQ(r.dem_steps, 0);
    EXPECT_EQ(rve.stress().norm(), 0.0);
  }
  EXPECT_NEAR(rve.free_volume(), 40 * 0.03, 1e-12);
  EXPECT_TRUE(same_bits(rve.simulation().cell().h, h_lost));
  EXPECT_EQ(rve.simulation().time(), t_lost);

  // The state round trip keeps the free volume, bit for bit.
  common::StateStore store;
  rve.save(store);
  dem::Rve back = dem::Rve::load(store);
  EXPECT_EQ(back.free_volume(), rve.free_volume());
  EXPECT_EQ(back.params().contact_loss, dem::ContactLoss::disconnected);
  EXPECT_EQ(back.params().rate, dem::RveRate::material);

  // Compression by half of the free volume: still held.
  const Mat3 c = -Mat3::Identity() * 1e4;
  for (int k = 0; k < 20; ++k) {
    const dem::StepReport r = rve.step(c, kDt);
    ASSERT_NE(r.guards & dem::kGuardDisconnected, 0u);
  }
  EXPECT_NEAR(rve.free_volume(), 20 * 0.03, 1e-12);
  EXPECT_TRUE(same_bits(rve.simulation().cell().h, h_lost));
  // 20 more close it (to rounding); the next one strains the cell, by one step's 3 % (less the
  // rounding left in the free volume), for the first time since the contacts were lost.
  for (int k = 0; k < 20; ++k) (void)rve.step(c, kDt);
  EXPECT_LT(rve.free_volume(), 1e-12);
  const dem::StepReport r = rve.step(c, kDt);
  EXPECT_EQ(r.guards & dem::kGuardDisconnected, 0u);
  EXPECT_GT(r.dem_steps, 0);
  EXPECT_EQ(rve.free_volume(), 0.0);
  const double jv = rve.simulation().cell().h.determinant() / h_lost.determinant();
  EXPECT_NEAR(std::log(jv), -0.03, 1e-4);  // the cell's product of (I + L dt_DEM): O(0.03^2 / n)
  // Compressed on, it reconnects and carries a pressure again.
  double p = 0.0;
  for (int k = 0; k < 200 && !(p > 1e3); ++k) p = rve.step(c * 0.2, kDt).p;
  EXPECT_GT(p, 1e3);
  EXPECT_EQ(rve.free_volume(), 0.0);

  // The restored copy continues bit for bit.
  dem::Rve again = dem::Rve::load(store);
  for (int k = 0; k < 3; ++k) {
    (void)back.step(c, kDt);
    (void)again.step(c, kDt);
  }
  EXPECT_EQ(back.free_volume(), again.free_volume());
  EXPECT_TRUE(same_bits(back.simulation().cell().h, again.simulation().cell().h));
}

TEST(ContactLoss, StrainedRveStretchesItsCell) {
  dem::Rve rve = without_contacts(dem::ContactLoss::strained);
  const Mat3 h_lost = rve.simulation().cell().h;
  const dem::StepReport r = rve.step(Mat3::Identity() * 1e4, 1e-6);
  EXPECT_EQ(r.guards & dem::kGuardDisconnected, 0u);
  EXPECT_GT(r.dem_steps, 0);
  // The cell's product of (I + L dt_DEM) over its DEM steps: exp(0.03) to O(0.03^2 / n).
  EXPECT_NEAR(std::log(rve.simulation().cell().h.determinant() / h_lost.determinant()), 0.03, 1e-4);
  EXPECT_EQ(rve.free_volume(), 0.0);
}

// A strained spray stretched far (a point at a column's front, pulled by its neighbours: x
// stretched and z thinned at constant volume, 10 % a step): its cell thins with the point until
// its spheres would no longer fit across it (the neighbour search's limit, 2 r_max + skin), then
// takes only the increments' volume change (kGuardSprayShape): no step fails, the spray keeps its
// volume and next to no stress (its grains collide now and then), and its cell stays wider than
// the limit. Before, the neighbour search stopped the run (exit 3).
TEST(ContactLoss, StrainedSprayStretchedBeyondItsCellKeepsItsShape) {
  dem::Rve rve = without_contacts(dem::ContactLoss::strained);
  for (int k = 0; k < 10; ++k) (void)rve.step(Mat3::Identity() * 1e4, 2e-6);  // dilute: ~0.2
  ASSERT_LT(solid_fraction(rve), 0.3);
  const double v0 = rve.simulation().cell().volume();
  const double r_max =
      *std::max_element(rve.simulation().spheres().r.begin(), rve.simulation().spheres().r.end());
  const double limit = (2.0 + rve.simulation().numerics().skin_factor) * r_max;
  Mat3 l = Mat3::Zero();
  l(0, 0) = 1e4;
  l(2, 2) = -1e4;
  int shaped = 0;
  double p_max = 0.0;
  for (int k = 0; k < 40; ++k) {
    dem::StepReport r;
    ASSERT_NO_THROW(r = rve.step(l, 1e-5)) << "step " << k;
    if ((r.guards & dem::kGuardSprayShape) != 0) ++shaped;
    p_max = std::max(p_max, r.p);
  }
  const dem::PeriodicCell& cell = rve.simulation().cell();
  std::printf(
      "steps that kept the shape: %d of 40; widths %.3g %.3g %.3g m, limit %.3g m; "
      "ln(V / V0) %.2e; largest p %.3g Pa\n",
      shaped, cell.width(0), cell.width(1), cell.width(2), limit, std::log(cell.volume() / v0),
      p_max);
  EXPECT_GT(shaped, 0);
  EXPECT_GE(std::min({cell.width(0), cell.width(1), cell.width(2)}), limit);
  // The isochoric steps that stretch the cell lose O(g^2 / n) of volume each to the product of
  // (I + L dt_DEM) over their n DEM steps (0.1^2 / n, n ~ 70 here); the shape-keeping ones none.
  EXPECT_NEAR(std::log(cell.volume() / v0), 0.0, 5e-3);
}

// dilute(): a solid fraction below disconnect_fraction, the material's (a held RVE's free volume
// counted), whatever the contacts: the dense packing is not, its spray is, on either side of the
// fraction to the bit.
TEST(ContactLoss, ASprayIsDiluteThePackingNot) {
  const dem::RveParams strained = params(dem::RveRate::material, dem::ContactLoss::strained);
  EXPECT_FALSE(dem::Rve(dem_test::reference_packing(), strained).dilute());
  dem::Rve spray = without_contacts(dem::ContactLoss::strained);
  EXPECT_TRUE(spray.dilute());
  const double phi = solid_fraction(spray);
  dem::RveParams p = strained;
  p.disconnect_fraction = std::nextafter(phi, 1.0);
  EXPECT_TRUE(dem::Rve::from_simulation(spray.simulation(), p).dilute());
  p.disconnect_fraction = phi;
  EXPECT_FALSE(dem::Rve::from_simulation(spray.simulation(), p).dilute());
  // Held with free volume f: its cell (fraction phi_c) does not move, the material it stands for
  // (phi_c exp(-f)) dilutes on. With the fraction between the two, the material's decides.
  dem::Rve held = without_contacts(dem::ContactLoss::disconnected);
  for (int k = 0; k < 5; ++k) (void)held.step(Mat3::Identity() * 1e4, 1e-6);
  const double f = held.free_volume();
  ASSERT_NEAR(f, 5 * 0.03, 1e-12);
  common::StateStore saved;
  held.save(saved);
  // The same state with disconnect_fraction = phi_c exp(-f / 2).
  common::StateStore edited = dem_test::copy_without(saved, "rve/params/disconnect_fraction");
  const double between = solid_fraction(held) * std::exp(-0.5 * f);
  edited.write("rve/params/disconnect_fraction", std::span<const double>(&between, 1));
  const dem::Rve back = dem::Rve::load(edited);
  ASSERT_EQ(back.params().disconnect_fraction, between);
  EXPECT_GT(solid_fraction(back), between);  // the cell alone would not be dilute
  EXPECT_TRUE(back.dilute());
}

// A state written before the keys existed continues as it ran: coupling rate, strained cell.
TEST(ContactLoss, StateWithoutTheKeysContinuesAsBefore) {
  dem::Rve rve(dem_test::reference_packing(),
               params(dem::RveRate::material, dem::ContactLoss::disconnected));
  common::StateStore store;
  rve.save(store);
  common::StateStore old;  // DEM state version 3, without the keys' fields
  const common::StateStore v3 = dem_test::as_former_version(store, 3);
  for (const auto& [name, field] : v3.fields()) {
    if (name == "rve/rate" || name == "rve/contact_loss" || name == "rve/free_volume") continue;
    std::visit([&old, &name](const auto& v) { old.write(name, std::span(v)); }, field);
  }
  const dem::Rve back = dem::Rve::load(old);
  EXPECT_EQ(back.params().rate, dem::RveRate::coupling);
  EXPECT_EQ(back.params().contact_loss, dem::ContactLoss::strained);
  // A free volume in a state that does not disconnect is refused by name.
  common::StateStore bad = old;
  bad.write("rve/free_volume", std::span<const double>(std::vector<double>{0.5}));
  try {
    (void)dem::Rve::load(bad);
    ADD_FAILURE() << "a free volume without contact_loss = disconnected was accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rve/free_volume"), std::string::npos) << e.what();
  }
}

}  // namespace

// dem.coupling.min_dem_steps: a small increment (T_p below one DEM step) runs over min_dem_steps
// DEM steps of the critical length, the same increment (the cells end equal), within the MPM step
// at the material rate; 1 (the default) keeps one DEM step. The minimum is part of the state.
TEST(RveRate, MinDemStepsRelaxesASmallIncrement) {
  const dem::Packing pk = dem_test::reference_packing();
  dem::RveParams p1 = params(dem::RveRate::material, dem::ContactLoss::disconnected);
  dem::RveParams p10 = p1;
  p10.min_dem_steps = 10;
  dem::Rve one(pk, p1);
  dem::Rve ten(pk, p10);
  const Mat3 l = simple_shear(1e-3);  // 1e-8 per MPM step of 1e-5 s: T_p far below one DEM step
  const double dt = 1e-5;
  const dem::StepReport a = one.step(l, dt);
  const dem::StepReport b = ten.step(l, dt);
  EXPECT_EQ(a.dem_steps, 1);
  EXPECT_EQ(a.guards & dem::kGuardMinSteps, 0u);
  EXPECT_EQ(b.dem_steps, 10);
  EXPECT_NE(b.guards & dem::kGuardMinSteps, 0u);
  EXPECT_NEAR(b.t_p, 10.0 * b.dt_dem, 1e-12 * b.t_p);
  EXPECT_LT(b.t_p, dt);
  EXPECT_TRUE(one.simulation().cell().h.isApprox(ten.simulation().cell().h, 1e-14));
  // An MPM step shorter than ten DEM steps: the material rate keeps the RVE within it.
  const dem::StepReport c = ten.step(l, 3.0 * b.dt_dem);
  EXPECT_LE(c.t_p, 3.0 * b.dt_dem * (1 + 1e-12));
  // Saved and read back.
  common::StateStore s;
  ten.save(s);
  EXPECT_EQ(s.read_i64("rve/params/min_dem_steps"), std::vector<std::int64_t>{10});
  const dem::Rve back = dem::Rve::load(s);
  common::StateStore again;
  back.save(again);
  EXPECT_EQ(again.read_i64("rve/params/min_dem_steps"), std::vector<std::int64_t>{10});
}
