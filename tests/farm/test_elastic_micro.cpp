// Unit tests of the ElasticMicro verification model (farm/elastic_micro.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "farm/elastic_micro.hpp"

namespace {

farm::ElasticMicroParams params() {
  farm::ElasticMicroParams p;
  p.material.young_modulus = 10e6;
  p.material.poisson_ratio = 0.2;
  p.density = 2000.0;
  p.initial_stress = -1e5 * common::Mat3::Identity();
  p.initial_stress(0, 1) = p.initial_stress(1, 0) = 2e4;
  return p;
}

// The state s (this version's) as an older version of ElasticMicro wrote it (the version history
// of farm/elastic_micro.hpp): versions 2 to 5 named the moduli after the C++ members and stored
// the angles in radians, those the app derived from the job's degrees (farm::to_radians), version 6
// as now; without the fields added since, with that version's number.
common::StateStore as_version(const common::StateStore& s, std::int64_t version) {
  const std::vector<std::pair<std::int64_t, std::string>> added = {
      {3, "elastic/params/friction_angle"},          {3, "elastic/free_volume"},
      {4, "elastic/params/dilatancy_angle"},         {5, "elastic/params/softening_strain"},
      {5, "elastic/params/residual_friction_angle"}, {5, "elastic/plastic_shear_strain"},
      {7, "elastic/params/dilatancy_cutoff"},        {7, "elastic/plastic_volumetric_strain"}};
  const std::vector<std::pair<std::string, std::string>> renamed = {
      {"elastic/params/young_modulus", "elastic/params/young"},
      {"elastic/params/poisson_ratio", "elastic/params/poisson"}};
  const std::vector<std::string> angles = {"elastic/params/friction_angle",
                                           "elastic/params/dilatancy_angle",
                                           "elastic/params/residual_friction_angle"};
  common::StateStore old;
  for (const auto& [name, field] : s.fields()) {
    const bool later = std::any_of(added.begin(), added.end(), [&](const auto& a) {
      return a.first > version && a.second == name;
    });
    if (later || name == "elastic/version") continue;
    std::string old_name = name;
    for (const auto& [now, then] : renamed) {
      if (name == now && version <= 5) old_name = then;
    }
    if (version <= 5 && std::find(angles.begin(), angles.end(), name) != angles.end()) {
      old.write(name, std::vector<double>{farm::to_radians(s.read_f64(name).at(0))});
      continue;
    }
    std::visit([&old, &old_name](const auto& values) { old.write(old_name, values); }, field);
  }
  old.write("elastic/version", std::vector<std::int64_t>{version});
  return old;
}

// Simple shear, 1 /s.
const common::Mat3 kShear = [] {
  common::Mat3 L = common::Mat3::Zero();
  L(0, 2) = 1.0;
  return L;
}();

// A model of these parameters from an isotropic 10 kPa, sheared by kShear for 50 steps.
farm::ElasticMicro sheared(const farm::ElasticMicroParams& p) {
  farm::ElasticMicro m(4, p, -1e4 * common::Mat3::Identity());
  for (int k = 0; k < 50; ++k) (void)m.step(kShear, 1e-4);
  return m;
}

// A model and its reloaded copy, stepped alike by L, keep the same stress bit for bit.
void expect_same_continuation(farm::MicroModel& a, farm::MicroModel& b, const common::Mat3& L) {
  for (int k = 0; k < 50; ++k) {
    (void)a.step(L, 1e-4);
    (void)b.step(L, 1e-4);
  }
  EXPECT_EQ(b.stress(), a.stress());
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
  const double E = p.material.young_modulus;
  const double nu = p.material.poisson_ratio;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
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
  p.material.young_modulus = -1;
  EXPECT_THROW(farm::ElasticMicro(1, p), common::InputError);
}

// Every parameter is a named field: the material's under its job key (kElasticMaterial, the angles
// in degrees), the others under the member they name; the state carries its version.
TEST(ElasticMicro, ParametersAreNamedFields) {
  farm::ElasticMicroParams p = params();
  p.substeps = 3;
  p.fail_id = 9;
  p.fail_step = 11;
  p.void_ratio0 = 0.55;
  p.material.friction_deg = 30.0;
  p.material.dilatancy_deg = 12.5;
  p.material.residual_friction_deg = 25.0;  // read only with softening_strain > 0, saved always
  const farm::ElasticMicro m(4, p);
  common::StateStore s;
  m.save(s);
  EXPECT_EQ(s.read_i64("elastic/version"), std::vector<std::int64_t>{7});
  EXPECT_EQ(s.read_i64("elastic/id"), std::vector<std::int64_t>{4});
  for (const auto& row : farm::kElasticMaterial) {
    EXPECT_EQ(s.read_f64("elastic/params/" + std::string(row.key)),
              std::vector<double>{row.get(p.material)})
        << row.key;
  }
  EXPECT_EQ(s.read_f64("elastic/params/young_modulus"), std::vector<double>{10e6});
  EXPECT_EQ(s.read_f64("elastic/params/poisson_ratio"), std::vector<double>{0.2});
  EXPECT_EQ(s.read_f64("elastic/params/friction_angle"), std::vector<double>{30.0});
  EXPECT_EQ(s.read_f64("elastic/params/dilatancy_angle"), std::vector<double>{12.5});
  EXPECT_EQ(s.read_f64("elastic/params/residual_friction_angle"), std::vector<double>{25.0});
  EXPECT_EQ(s.read_f64("elastic/params/softening_strain"), std::vector<double>{0.0});
  EXPECT_EQ(s.read_f64("elastic/params/dilatancy_cutoff"), std::vector<double>{0.0});
  EXPECT_EQ(s.read_f64("elastic/params/density"), std::vector<double>{p.density});
  EXPECT_EQ(s.read_f64("elastic/params/void_ratio0"), std::vector<double>{0.55});
  const auto s0 = s.read_f64("elastic/params/initial_stress");
  ASSERT_EQ(s0.size(), 9u);
  EXPECT_EQ(s0[1], p.initial_stress(0, 1));  // row-major
  EXPECT_EQ(s0[8], p.initial_stress(2, 2));
  EXPECT_EQ(s.read_f64("elastic/plastic_shear_strain"), std::vector<double>{0.0});
  EXPECT_EQ(s.read_f64("elastic/plastic_volumetric_strain"), std::vector<double>{0.0});
  EXPECT_EQ(s.read_i64("elastic/params/substeps"), std::vector<std::int64_t>{3});
  EXPECT_EQ(s.read_i64("elastic/params/fail_id"), std::vector<std::int64_t>{9});
  EXPECT_EQ(s.read_i64("elastic/params/fail_step"), std::vector<std::int64_t>{11});
  for (const char* former :
       {"elastic/params", "elastic/int_params", "elastic/params/young", "elastic/params/poisson"}) {
    EXPECT_FALSE(s.has(former)) << former;
  }
  common::StateStore again;
  farm::ElasticMicro::load(s)->save(again);
  EXPECT_TRUE(again.fields() == s.fields());
}

// A version-7 state of a dilatant frictional model with a cut-off, saved mid-shear below its
// cut-off, comes back with the same fields and continues bit for bit through the cut-off (two
// sub-steps per step); a version-7 state without either new field is refused naming it.
TEST(ElasticMicro, Version7RoundTripsAndContinuesBitForBit) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 37.3;
  p.material.dilatancy_deg = 8.1;
  p.material.dilatancy_cutoff = 6e-4;
  p.substeps = 2;
  farm::ElasticMicro m = sheared(p);
  common::StateStore s;
  m.save(s);
  ASSERT_EQ(s.read_i64("elastic/version"), std::vector<std::int64_t>{7});
  const double before = s.read_f64("elastic/plastic_volumetric_strain").at(0);
  ASSERT_GT(before, 0.0);
  ASSERT_LT(before, p.material.dilatancy_cutoff);
  const auto loaded = farm::ElasticMicro::load(common::StateStore::deserialize(s.serialize()));
  common::StateStore again;
  loaded->save(again);
  EXPECT_TRUE(again.fields() == s.fields());
  expect_same_continuation(m, *loaded, kShear);
  common::StateStore after;
  loaded->save(after);
  EXPECT_GE(after.read_f64("elastic/plastic_volumetric_strain").at(0), p.material.dilatancy_cutoff);
  for (const std::string missing :
       {"elastic/params/dilatancy_cutoff", "elastic/plastic_volumetric_strain"}) {
    common::StateStore without;
    for (const auto& [name, field] : s.fields()) {
      if (name != missing) std::visit([&](const auto& v) { without.write(name, v); }, field);
    }
    try {
      (void)farm::ElasticMicro::load(without);
      ADD_FAILURE() << "a version-7 state without " << missing << " was loaded";
    } catch (const common::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
  }
}

// A version-6 state (before the cut-off) is read without a cut-off and with no plastic dilation so
// far, and continues as the same state saved by this version would.
TEST(ElasticMicro, Version6IsReadWithoutCutoff) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 34.0;
  p.material.dilatancy_deg = 11.0;
  farm::ElasticMicro m = sheared(p);
  common::StateStore s;
  m.save(s);
  const auto loaded = farm::ElasticMicro::load(as_version(s, 6));
  common::StateStore again;
  loaded->save(again);
  EXPECT_EQ(again.read_i64("elastic/version"), std::vector<std::int64_t>{7});
  EXPECT_EQ(again.read_f64("elastic/params/dilatancy_cutoff"), std::vector<double>{0.0});
  EXPECT_EQ(again.read_f64("elastic/plastic_volumetric_strain"), std::vector<double>{0.0});
  expect_same_continuation(m, *loaded, kShear);
}

// A version-5 state, written here field by field with that version's names and radians (those the
// app derived from the job's degrees), is read with those radians and continues bit for bit as
// the model of the same radians; saved again (this version, degrees) and read, it still does.
TEST(ElasticMicro, Version5StateIsReadWithItsRadiansAndContinuesBitForBit) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 41.7;
  p.material.residual_friction_deg = 33.3;
  p.material.softening_strain = 0.05;
  p.substeps = 2;
  farm::ElasticMicro m(7, p, -1e4 * common::Mat3::Identity());
  for (int k = 0; k < 300; ++k) (void)m.step(kShear, 1e-4);  // onto the softening branch
  common::StateStore now;
  m.save(now);
  ASSERT_GT(now.read_f64("elastic/plastic_shear_strain").at(0), 0.0);
  common::StateStore v5;
  v5.write("elastic/version", std::vector<std::int64_t>{5});
  v5.write("elastic/id", std::vector<std::int64_t>{7});
  v5.write("elastic/params/young", std::vector<double>{10e6});
  v5.write("elastic/params/poisson", std::vector<double>{0.2});
  v5.write("elastic/params/density", std::vector<double>{2000.0});
  v5.write("elastic/params/void_ratio0", std::vector<double>{0.6});
  v5.write("elastic/params/friction_angle", std::vector<double>{41.7 * M_PI / 180.0});
  v5.write("elastic/params/dilatancy_angle", std::vector<double>{0.0});
  v5.write("elastic/params/softening_strain", std::vector<double>{0.05});
  v5.write("elastic/params/residual_friction_angle", std::vector<double>{33.3 * M_PI / 180.0});
  v5.write("elastic/params/substeps", std::vector<std::int64_t>{2});
  v5.write("elastic/params/fail_id", std::vector<std::int64_t>{-1});
  v5.write("elastic/params/fail_step", std::vector<std::int64_t>{-1});
  for (const char* name : {"elastic/params/initial_stress", "elastic/stress", "elastic/j",
                           "elastic/free_volume", "elastic/plastic_shear_strain"}) {
    v5.write(name, now.read_f64(name));
  }
  v5.write("elastic/steps", now.read_i64("elastic/steps"));
  const auto loaded = farm::ElasticMicro::load(v5);
  common::StateStore as_v6;
  loaded->save(as_v6);
  EXPECT_EQ(as_v6.read_i64("elastic/version"), std::vector<std::int64_t>{7});
  // The degrees are the job's, whose radians the state held (farm::degrees_of_radians).
  EXPECT_EQ(as_v6.read_f64("elastic/params/friction_angle"), std::vector<double>{41.7});
  EXPECT_EQ(as_v6.read_f64("elastic/params/residual_friction_angle"), std::vector<double>{33.3});
  EXPECT_EQ(as_v6.read_f64("elastic/params/young_modulus"), std::vector<double>{10e6});
  EXPECT_EQ(as_v6.read_f64("elastic/params/softening_strain"), std::vector<double>{0.05});
  const auto reloaded = farm::ElasticMicro::load(as_v6);
  for (int k = 0; k < 300; ++k) {
    (void)m.step(kShear, 1e-4);
    (void)loaded->step(kShear, 1e-4);
    (void)reloaded->step(kShear, 1e-4);
  }
  EXPECT_EQ(std::memcmp(m.stress().data(), loaded->stress().data(), 9 * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(m.stress().data(), reloaded->stress().data(), 9 * sizeof(double)), 0);
  common::StateStore a;
  common::StateStore b;
  m.save(a);
  loaded->save(b);
  EXPECT_EQ(b.read_f64("elastic/plastic_shear_strain"), a.read_f64("elastic/plastic_shear_strain"));
}

// A version-5 state's radians that no job's degrees give (the C++ API of then took radians) are the
// model's as they were: a friction angle of 0.6 rad bounds the shear stress by p0 sin(0.6).
TEST(ElasticMicro, Version5RadiansAreTheModelsUnconverted) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 30.0;
  common::StateStore s;
  farm::ElasticMicro(4, p, -1e4 * common::Mat3::Identity()).save(s);
  common::StateStore v5 = as_version(s, 5);
  // 0.6 rad against the 0.5236 of 30 deg: the loaded model must use 0.6 rad, its cone sin(0.6).
  common::StateStore edited;
  for (const auto& [name, field] : v5.fields()) {
    if (name != "elastic/params/friction_angle") {
      std::visit([&](const auto& v) { edited.write(name, v); }, field);
    }
  }
  edited.write("elastic/params/friction_angle", std::vector<double>{0.6});
  const auto m = farm::ElasticMicro::load(edited);
  for (int k = 0; k < 400; ++k) (void)m->step(kShear, 1e-4);  // gamma = 0.04, on the cone
  EXPECT_NEAR(std::abs(m->stress()(0, 2)), 1e4 * std::sin(0.6), 0.01 * 1e4);
}

// A state of version 1 (positional arrays, no elastic/version) is refused with a message naming
// the field and both versions.
TEST(ElasticMicro, OldVersionRefused) {
  common::StateStore s;
  s.write("elastic/id", std::vector<std::int64_t>{1});
  s.write("elastic/params", std::vector<double>(13, 1.0));
  s.write("elastic/int_params", std::vector<std::int64_t>{1, -1, -1});
  try {
    (void)farm::ElasticMicro::load(s);
    ADD_FAILURE() << "a version-1 state was loaded";
  } catch (const common::InputError& e) {
    const std::string m = e.what();
    for (const char* needle : {"'elastic/version' = 1 (absent)", "reads versions 2 to 7 only",
                               "elastic/params/young", "elastic/params/young_modulus"}) {
      EXPECT_NE(m.find(needle), std::string::npos) << m;
    }
  }
}

// A state of a version this build does not know (a later one) is refused naming the field, the
// version and the versions it reads.
TEST(ElasticMicro, LaterVersionRefused) {
  common::StateStore s;
  farm::ElasticMicro(1, params()).save(s);
  common::StateStore later;
  for (const auto& [name, field] : s.fields()) {
    if (name != "elastic/version") std::visit([&](const auto& v) { later.write(name, v); }, field);
  }
  later.write("elastic/version", std::vector<std::int64_t>{8});
  try {
    (void)farm::ElasticMicro::load(later);
    ADD_FAILURE() << "a version-8 state was loaded";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "field 'elastic/version' = 8: this build reads versions 2 to 7 only"),
              std::string::npos)
        << e.what();
  }
}

// A version-2 state (before the friction angle) is read as a linear elastic model and continues.
TEST(ElasticMicro, Version2IsReadAsElastic) {
  const farm::ElasticMicro m(4, params());
  common::StateStore s;
  m.save(s);
  const common::StateStore v2 = as_version(s, 2);
  const auto loaded = farm::ElasticMicro::load(v2);
  common::StateStore again;
  loaded->save(again);
  EXPECT_EQ(again.read_f64("elastic/params/friction_angle"), std::vector<double>{0.0});
  EXPECT_EQ(again.read_f64("elastic/params/dilatancy_angle"), std::vector<double>{0.0});
  EXPECT_EQ(again.read_f64("elastic/params/young_modulus"), std::vector<double>{10e6});
  EXPECT_EQ(again.read_f64("elastic/stress"), s.read_f64("elastic/stress"));
}

// A version-3 state (before the dilatancy angle) is read with a deviatoric flow and continues as
// the same state saved by this version would.
TEST(ElasticMicro, Version3IsReadWithoutDilatancy) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 34.0;
  farm::ElasticMicro m = sheared(p);
  common::StateStore s;
  m.save(s);
  const common::StateStore v3 = as_version(s, 3);
  const auto loaded = farm::ElasticMicro::load(v3);
  expect_same_continuation(m, *loaded, kShear);
}

// A version-4 state (before the softening) is read without softening and continues as the same
// state saved by this version would.
TEST(ElasticMicro, Version4IsReadWithoutSoftening) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 34.0;
  p.material.dilatancy_deg = 11.0;
  farm::ElasticMicro m = sheared(p);
  common::StateStore s;
  m.save(s);
  const common::StateStore v4 = as_version(s, 4);
  const auto loaded = farm::ElasticMicro::load(v4);
  common::StateStore again;
  loaded->save(again);
  EXPECT_EQ(again.read_f64("elastic/params/softening_strain"), std::vector<double>{0.0});
  EXPECT_EQ(farm::to_radians(again.read_f64("elastic/params/residual_friction_angle").at(0)),
            farm::to_radians(34.0));
  expect_same_continuation(m, *loaded, kShear);
}

// With softening, a simple shear at constant volume mobilises the peak friction, then falls to
// the residual one (tau = p0 sin(phi)); a state saved on the softening branch continues bit for
// bit, carrying its plastic shear strain.
TEST(ElasticMicro, SofteningFallsFromPeakToResidualFriction) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 40.0;
  p.material.residual_friction_deg = 30.0;
  p.material.softening_strain = 0.05;
  const double p0 = 1e5;
  farm::ElasticMicro m(0, p, -p0 * common::Mat3::Identity());
  common::Mat3 L = common::Mat3::Zero();
  L(0, 2) = 1.0;  // simple shear, 1 /s
  double peak = 0.0;
  std::unique_ptr<farm::MicroModel> copy;
  for (int k = 1; k <= 1500; ++k) {  // gamma = 0.15: three times the softening strain
    (void)m.step(L, 1e-4);
    peak = std::max(peak, std::abs(m.stress()(0, 2)));
    if (copy) (void)copy->step(L, 1e-4);
    if (k == 400) {
      common::StateStore s;
      m.save(s);
      const double gamma_p = s.read_f64("elastic/plastic_shear_strain")[0];
      EXPECT_GT(gamma_p, 0.0);
      EXPECT_LT(gamma_p, p.material.softening_strain);  // on the softening branch
      copy = farm::ElasticMicro::load(s);
    }
  }
  EXPECT_NEAR(peak, p0 * std::sin(40.0 * M_PI / 180.0), 0.01 * p0);
  EXPECT_NEAR(std::abs(m.stress()(0, 2)), p0 * std::sin(30.0 * M_PI / 180.0), 0.01 * p0);
  EXPECT_TRUE(copy->stress() == m.stress());
}

// Softening needs a friction angle and a deviatoric flow, and a residual angle not above the peak.
TEST(ElasticMicro, SofteningParametersAreChecked) {
  farm::ElasticMicroParams p = params();
  p.material.softening_strain = 0.05;
  EXPECT_THROW(farm::ElasticMicro(0, p), common::InputError);  // no friction angle
  p.material.friction_deg = 34.0;
  p.material.residual_friction_deg = 40.0;
  EXPECT_THROW(farm::ElasticMicro(0, p), common::InputError);  // residual above the peak
  p.material.residual_friction_deg = 28.0;
  p.material.dilatancy_deg = 6.0;
  EXPECT_THROW(farm::ElasticMicro(0, p), common::InputError);  // dilatant
  p.material.dilatancy_deg = 0.0;
  EXPECT_NO_THROW(farm::ElasticMicro(0, p));
  p.material.softening_strain = -1.0;
  EXPECT_THROW(farm::ElasticMicro(0, p), common::InputError);
}

// With a friction angle the model is elastic-perfectly plastic: a simple shear at constant volume
// from an isotropic stress p0 ends on the cone, tau = p0 sin(phi) (no dilatancy: p stays p0).
TEST(ElasticMicro, FrictionAngleBoundsTheShearStress) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 30.0;
  const double p0 = 10e3;
  farm::ElasticMicro m(0, p, -p0 * common::Mat3::Identity());
  common::Mat3 L = common::Mat3::Zero();
  L(0, 2) = 1.0;                                        // v_x = z: simple shear, 1 /s
  for (int k = 0; k < 400; ++k) (void)m.step(L, 1e-4);  // gamma = 0.04, far beyond yield
  const common::Mat3 s = m.stress();
  EXPECT_NEAR(-s.trace() / 3.0, p0, 1e-9 * p0);
  EXPECT_NEAR(std::abs(s(0, 2)), p0 * 0.5, 0.01 * p0 * 0.5);
  const farm::MicroReport r = m.report();
  EXPECT_NEAR(r.q, std::sqrt(3.0) * p0 * 0.5, 1e-6 * p0);  // on the cone: q = sqrt(3 J2)
}

// With a dilatancy angle the flow is that of plane-strain Mohr-Coulomb (mpm::plane_strain_cone):
// driven along the plastic flow direction of MC in plane strain (y fixed, z compressed, x
// extended so that the volume grows at sin(psi) of the shear), the stress settles where the
// elastic strain rate vanishes: the in-plane stress ratio is sin(phi) and the state stays put.
// The check is independent of the cone's formulas: only Mohr-Coulomb's angles enter it.
TEST(ElasticMicro, DilatantFlowMatchesPlaneStrainMohrCoulomb) {
  for (const double phi_deg : {30.0, 40.0}) {
    for (const double psi_deg : {0.0, 10.0, phi_deg}) {
      farm::ElasticMicroParams p = params();
      p.material.friction_deg = phi_deg;
      p.material.dilatancy_deg = psi_deg;
      farm::ElasticMicro m(0, p, -10e3 * common::Mat3::Identity());
      const double sin_psi = std::sin(psi_deg * M_PI / 180.0);
      common::Mat3 L = common::Mat3::Zero();
      L(2, 2) = -1.0;                               // eps_3 (major, compression), 1 /s
      L(0, 0) = (1.0 + sin_psi) / (1.0 - sin_psi);  // eps_1: (e1 + e3) / (e1 - e3) = sin(psi)
      for (int k = 0; k < 3000; ++k) (void)m.step(L, 1e-5);  // 3 % axial, far beyond yield
      const common::Mat3 before = m.stress();
      (void)m.step(L, 1e-5);
      const common::Mat3 s = m.stress();
      const double ratio = (s(0, 0) - s(2, 2)) / -(s(0, 0) + s(2, 2));
      SCOPED_TRACE(testing::Message() << "phi " << phi_deg << " psi " << psi_deg);
      EXPECT_NEAR(ratio, std::sin(phi_deg * M_PI / 180.0), 1e-6);
      EXPECT_LT((s - before).norm(), 1e-6 * s.norm());  // a steady plastic flow
    }
  }
}

// The dilatancy cut-off: a simple shear at constant volume from an isotropic p0 raises p by K
// tr(d eps_p) while the material dilates (the volume is held: the plastic dilation compresses it
// elastically), then, past the cut-off, the flow is deviatoric and p stays; the stress lies on the
// cone of the same friction angle without dilatancy, sqrt(J2) = sin(phi) p (while it dilated,
// the lower slope of the dilatant cone). Without a cut-off p keeps rising. The plastic dilation
// passes the cut-off by at most one step's increment.
TEST(ElasticMicro, DilatancyStopsAtTheCutoff) {
  const double p0 = 1e4;
  const double cutoff = 0.005;
  auto run = [&](double c, int steps) {
    farm::ElasticMicroParams p = params();
    p.material.friction_deg = 40.0;
    p.material.dilatancy_deg = 20.0;
    p.material.dilatancy_cutoff = c;
    farm::ElasticMicro m(0, p, -p0 * common::Mat3::Identity());
    for (int k = 0; k < steps; ++k) (void)m.step(kShear, 1e-4);
    return m;
  };
  const double bulk = 10e6 / (3.0 * (1.0 - 2.0 * 0.2));
  farm::ElasticMicro m = run(cutoff, 2000);  // gamma = 0.2
  common::StateStore s;
  m.save(s);
  const double dilation = s.read_f64("elastic/plastic_volumetric_strain").at(0);
  EXPECT_GE(dilation, cutoff);
  EXPECT_LT(dilation, cutoff + 1e-4);  // one step: tr(d eps_p) <= eta_bar gamma_dot dt
  const double p = -m.stress().trace() / 3.0;
  EXPECT_NEAR(p, p0 + bulk * dilation, 1e-9 * bulk);
  const common::Mat3 dev = m.stress() + p * common::Mat3::Identity();
  EXPECT_NEAR(std::sqrt(0.5 * dev.squaredNorm()), std::sin(40.0 * M_PI / 180.0) * p, 1e-6 * p);
  // The same material without a cut-off has dilated far beyond it (0.052), under a higher
  // pressure.
  farm::ElasticMicro free = run(0.0, 2000);
  common::StateStore f;
  free.save(f);
  EXPECT_GT(f.read_f64("elastic/plastic_volumetric_strain").at(0), 8.0 * cutoff);
  EXPECT_GT(-free.stress().trace() / 3.0, 2.0 * p);
  // A material below its cut-off is the material without one, bit for bit.
  EXPECT_TRUE(run(cutoff, 20).stress() == run(0.0, 20).stress());
}

// A frictional material pulled apart is disconnected: stress-free while its free volume lasts, and
// a compression first closes that volume, then loads it again (no stress at a tenth of the
// density).
TEST(ElasticMicro, DilatedFrictionalMaterialCarriesNoStressUntilRecompressed) {
  farm::ElasticMicroParams p = params();
  p.material.friction_deg = 30.0;
  const double p0 = 1e3;
  farm::ElasticMicro m(0, p, -p0 * common::Mat3::Identity());
  const common::Mat3 I = common::Mat3::Identity();
  auto volumetric = [](double a, double dt) { return 3.0 * std::log1p(a * dt); };  // L = a I
  double v = 0.0;
  for (int k = 0; k < 100; ++k) {  // ln(V / V0) = 0.3
    (void)m.step(I, 1e-3);
    v += volumetric(1.0, 1e-3);
  }
  EXPECT_TRUE(m.stress() == common::Mat3::Zero());
  const double bulk = p.material.young_modulus / (3.0 * (1.0 - 2.0 * p.material.poisson_ratio));
  const double free = v - p0 / bulk;  // the elastic unloading took p0 / K of the dilation
  // Compress back by about 0.2: still disconnected.
  double back = 0.0;
  for (int k = 0; k < 200; ++k) {
    (void)m.step(-I, 3.3e-4);
    back -= volumetric(-1.0, 3.3e-4);
  }
  ASSERT_LT(back, free);
  EXPECT_TRUE(m.stress() == common::Mat3::Zero());
  // Close the rest plus a strain of 1e-4 in one step: only the last part of the step loads it
  // (the hypoelastic increment K tr(D) h over that part).
  const double a = -1.0;
  const double dt = std::expm1(-(free - back + 1e-4) / 3.0) / a;  // volumetric(a, dt) = -(...)
  (void)m.step(a * I, dt);
  const double remainder = 1e-4 / (free - back + 1e-4);  // the fraction of the step that loads it
  EXPECT_NEAR(-m.stress().trace() / 3.0, -bulk * 3.0 * a * remainder * dt, 1e-6 * bulk * 1e-4);
  common::StateStore s;
  m.save(s);
  EXPECT_EQ(s.read_f64("elastic/free_volume"), std::vector<double>{0.0});
}

TEST(ElasticMicro, LoadRefusesMissingField) {
  common::StateStore s;
  s.write("elastic/id", std::vector<std::int64_t>{1});
  EXPECT_THROW(farm::ElasticMicro::load(s), common::InputError);
}

// A state's stress or volume ratio that is not finite is refused naming the field.
TEST(ElasticMicro, LoadRefusesValuesNotFinite) {
  farm::ElasticMicro a(5, params());
  common::StateStore good;
  a.save(good);
  const auto with = [&good](const std::string& field, std::vector<double> value) {
    common::StateStore out;
    for (const auto& [name, f] : good.fields()) {
      if (name != field) std::visit([&](const auto& v) { out.write(name, v); }, f);
    }
    out.write(field, value);
    return out;
  };
  std::vector<double> st = good.read_f64("elastic/stress");
  st[5] = std::nan("");
  for (const auto& [state, needle] :
       {std::pair{with("elastic/stress", st), std::string("'elastic/stress' value 5 is nan")},
        std::pair{with("elastic/j", {HUGE_VAL}), std::string("'elastic/j' = inf")}}) {
    try {
      (void)farm::ElasticMicro::load(state);
      ADD_FAILURE() << needle;
    } catch (const common::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}
