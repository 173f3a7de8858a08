// Tests of dem/state.hpp and the Rve's save/load: every parameter is a named field holding the
// member it names, the state carries its version, and a state of another version is refused with
// a message naming the field and both versions.
#include "dem/state.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "dem/loading.hpp"
#include "dem/rve.hpp"
#include "dem_test_util.hpp"

namespace {

/// An RVE whose parameters all differ from their defaults and from each other.
dem::Rve distinct_rve() {
  dem::RveParams p;
  p.material = dem_test::reference_material();
  p.material.alpha_t = 0.7;
  p.material.eta_t = 0.4;
  p.numerics.damping = 0.21;
  p.numerics.dt_safety = 0.75;
  p.numerics.skin_factor = 0.13;
  p.numerics.skin_min_factor = 0.035;
  p.numerics.timestep_update_interval = 77;
  p.numerics.max_skew = 0.55;
  p.inertial_number = 3e-4;
  p.d50 = 0.0;  // taken from the spheres: rve/d50_used differs from rve/d50
  p.p_floor = 1234.0;
  p.max_strain_per_step = 2e-5;
  p.max_steps_per_call = 5000;
  return dem::Rve(dem_test::reference_packing(), p);
}

/// A copy of `s` with `name` replaced by `value` (a StateStore field is written once).
template <class T>
common::StateStore with_field(const common::StateStore& s, const std::string& name,
                              std::vector<T> value) {
  common::StateStore out;
  for (const auto& [n, f] : s.fields()) {
    if (n == name) continue;
    std::visit([&out, &n](const auto& v) { out.write(n, std::span(v.data(), v.size())); }, f);
  }
  out.write(name, std::span<const T>(value));
  return out;
}
common::StateStore with_field(const common::StateStore& s, const std::string& name,
                              std::initializer_list<std::int64_t> value) {
  return with_field(s, name, std::vector<std::int64_t>(value));
}

/// `name`'s values with value k replaced by v.
template <class T>
std::vector<T> changed(const common::StateStore& s, const std::string& name, std::size_t k, T v) {
  std::vector<T> out;
  if constexpr (std::is_same_v<T, double>) {
    out = s.read_f64(name);
  } else {
    out = s.read_i64(name);
  }
  out.at(k) = v;
  return out;
}

/// Steps a and b `steps` times; expects their saved states to be the same bits and returns b's.
common::StateStore continue_both(dem::Simulation& a, dem::Simulation& b, int steps) {
  for (int k = 0; k < steps; ++k) {
    a.step();
    b.step();
  }
  common::StateStore sa;
  common::StateStore sb;
  dem::save_simulation(a, sa);
  dem::save_simulation(b, sb);
  EXPECT_TRUE(sa.fields() == sb.fields());
  return sb;
}

}  // namespace

// Each name holds the member it names (written out here, not taken from the code's own table).
TEST(State, ParametersAreNamedScalarFields) {
  const dem::Rve rve = distinct_rve();
  common::StateStore s;
  rve.save(s);
  const dem::RveParams& p = rve.params();
  const std::vector<std::pair<const char*, double>> expected{
      {"params/material/density", p.material.density},
      {"params/material/young", p.material.young},
      {"params/material/ks_over_kn", p.material.ks_over_kn},
      {"params/material/friction_deg", p.material.friction_deg},
      {"params/material/alpha_r", p.material.alpha_r},
      {"params/material/eta_r", p.material.eta_r},
      {"params/material/alpha_t", p.material.alpha_t},
      {"params/material/eta_t", p.material.eta_t},
      {"params/numerics/damping", p.numerics.damping},
      {"params/numerics/dt_safety", p.numerics.dt_safety},
      {"params/numerics/skin_factor", p.numerics.skin_factor},
      {"params/numerics/skin_min_factor", p.numerics.skin_min_factor},
      {"params/numerics/max_skew", p.numerics.max_skew},
      {"rve/inertial_number", p.inertial_number},
      {"rve/d50", p.d50},
      {"rve/p_floor", p.p_floor},
      {"rve/max_strain_per_step", p.max_strain_per_step},
      {"rve/initial_pressure", p.initial_pressure},
      {"rve/d50_used", rve.d50()},
      {"verlet/skin", rve.simulation().verlet().skin},
      {"counters/dt", rve.simulation().dt()},
  };
  for (const auto& [name, value] : expected) {
    EXPECT_EQ(s.read_f64(name), std::vector<double>{value}) << name;
  }
  EXPECT_EQ(s.read_i64("params/numerics/timestep_update_interval"), std::vector<std::int64_t>{77});
  EXPECT_EQ(s.read_i64("verlet/built_at_step"),
            std::vector<std::int64_t>{rve.simulation().verlet().built_at_step});
  EXPECT_EQ(s.read_i64("verlet/shell_pairs"),
            std::vector<std::int64_t>{rve.simulation().verlet().shell_pairs});
  EXPECT_GT(rve.simulation().verlet().shell_pairs, 0);
  EXPECT_EQ(s.read_i64("rve/max_steps_per_call"), std::vector<std::int64_t>{5000});
  EXPECT_EQ(s.read_i64("dem/version"), std::vector<std::int64_t>{dem::kStateVersion});
  for (const char* old : {"params/material", "params/numerics", "rve/params", "contacts/props",
                          "verlet/skin_rmax", "counters/time_dt"}) {
    EXPECT_FALSE(s.has(old)) << old;
  }
  // Loading gives back the same parameters, member by member.
  const dem::Rve back = dem::Rve::load(s);
  common::StateStore again;
  back.save(again);
  EXPECT_TRUE(again.fields() == s.fields());
}

// The standalone sample's time-step interval was written as params/numerics/dt_refresh before the
// RVEs' own dt_refresh took that name alone: a state of then is read with its value.
TEST(State, TheTimestepIntervalIsReadUnderItsFormerName) {
  const dem::Rve rve = distinct_rve();
  common::StateStore s;
  rve.save(s);
  common::StateStore before;
  for (const auto& [n, f] : s.fields()) {
    const std::string name = n == "params/numerics/timestep_update_interval"
                                 ? std::string("params/numerics/dt_refresh")
                                 : n;
    std::visit([&](const auto& v) { before.write(name, std::span(v.data(), v.size())); }, f);
  }
  ASSERT_FALSE(before.has("params/numerics/timestep_update_interval"));
  EXPECT_EQ(dem::Rve::load(before).params().numerics.timestep_update_interval, 77);
}

TEST(State, ContactPropertiesAreNamedPerContactFields) {
  const dem::Rve rve = distinct_rve();
  common::StateStore s;
  rve.save(s);
  const dem::Contacts& c = rve.simulation().contacts();
  ASSERT_GT(c.size(), 0u);
  const auto tan_phi = s.read_f64("contacts/tan_phi");
  ASSERT_EQ(tan_phi.size(), c.size());
  for (std::size_t p = 0; p < c.size(); ++p) EXPECT_EQ(tan_phi[p], c.tan_phi[p]);
  // The other properties follow from the radii, the normal force from the branch: not stored
  // since version 3.
  for (const char* derived : {"contacts/kn", "contacts/ks", "contacts/kr", "contacts/kt",
                              "contacts/roll_cap", "contacts/twist_cap", "contacts/normal_force"}) {
    EXPECT_FALSE(s.has(derived)) << derived;
  }
}

TEST(State, OtherVersionIsRefusedNamingFieldAndVersions) {
  common::StateStore s;
  distinct_rve().save(s);
  const common::StateStore v1 = with_field(s, "dem/version", {1});
  for (const auto& load : {+[](const common::StateStore& st) { (void)dem::Rve::load(st); },
                           +[](const common::StateStore& st) { (void)dem::load_simulation(st); }}) {
    try {
      load(v1);
      ADD_FAILURE() << "a version-1 state was loaded";
    } catch (const common::InputError& e) {
      const std::string m = e.what();
      for (const char* needle :
           {"'dem/version' = 1", "reads versions 2, 3 and 4 only", "params/material"}) {
        EXPECT_NE(m.find(needle), std::string::npos) << m;
      }
    }
  }
  EXPECT_THROW((void)dem::Rve::load(with_field(s, "dem/version", {4})), common::InputError);
}

// Version 2 stored every contact property and the normal force per pair; version 3 only tan_phi
// (the others follow from the radii, the normal force from the branch). A version-2 state (here:
// a version-3 one given the seven fields, their values scrambled: they are not read) loads and
// continues with the same bits as the version-3 one.
TEST(State, Version2IsReadAndContinuesAsVersion3) {
  const dem::Rve rve = distinct_rve();
  common::StateStore v3;
  rve.save(v3);
  const std::size_t np = rve.simulation().contacts().size();
  ASSERT_GT(np, 0u);
  common::StateStore v2 = with_field(v3, "dem/version", {2});
  for (const char* f : {"kn", "ks", "kr", "kt", "roll_cap", "twist_cap", "normal_force"}) {
    v2.write(std::string("contacts/") + f, std::span<const double>(std::vector<double>(np, 7.0)));
  }
  dem::Simulation a = dem::load_simulation(v3);
  dem::Simulation b = dem::load_simulation(v2);
  std::int64_t touching = 0;
  for (std::size_t p = 0; p < np; ++p) touching += a.contacts().active[p];
  ASSERT_GT(touching, 0);
  const common::StateStore sb = continue_both(a, b, 300);
  EXPECT_EQ(sb.read_i64("dem/version"), std::vector<std::int64_t>{dem::kStateVersion});
}

// A Hertz-Mindlin state is version 4 (a build that knows only the CohFrict law refuses it by its
// version), carries the law and its parameters by name, and continues bit for bit after a load;
// a version-4 state naming another law is refused, naming the field.
TEST(State, HertzMindlinStateIsVersion4AndContinuesBitForBit) {
  dem::Material m = dem::hertz_mindlin_reference_material();
  m.hm.ktwist = 2e-5;
  dem::Simulation a = dem::make_simulation(dem_test::hertz_mindlin_packing(), m, dem::Numerics{});
  a.cell().l(2, 2) = -5.0;  // compress, so that contacts slide, roll and twist
  a.refresh_dt();
  for (int k = 0; k < 100; ++k) a.step();
  common::StateStore s;
  dem::save_simulation(a, s);
  EXPECT_EQ(s.read_i64("dem/version"), std::vector<std::int64_t>{dem::kStateVersionOtherLaw});
  EXPECT_EQ(s.read_i64("params/material/contact_law"), std::vector<std::int64_t>{1});
  EXPECT_EQ(s.read_f64("params/material/hertz_mindlin/krot"), std::vector<double>{1e-4});
  EXPECT_EQ(s.read_f64("params/material/hertz_mindlin/ktwist"), std::vector<double>{2e-5});
  dem::Simulation b = dem::load_simulation(s);
  EXPECT_EQ(b.law().kind(), dem::ContactLawKind::hertz_mindlin);
  (void)continue_both(a, b, 200);
  try {
    (void)dem::load_simulation(with_field(s, "params/material/contact_law", {7}));
    ADD_FAILURE() << "a version-4 state of an unknown law was read";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'params/material/contact_law' = 7"), std::string::npos)
        << e.what();
  }
}

// A state is checkpoint input: values that would let a run go on wrongly instead of failing (a
// NaN drops out of the comparisons that guard the neighbour list; a skin of 0 or an r_max below
// the largest radius lets contacts form unseen; a pair of a sphere with itself has no normal)
// are refused, naming the field. One example per rule; the rules cover every field of the kind.
TEST(State, ValuesThatWouldMisleadTheRunAreRefusedNamingTheField) {
  common::StateStore s;
  distinct_rve().save(s);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double r_max = s.read_f64("verlet/r_max")[0];
  struct Case {
    common::StateStore state;
    const char* field;
    const char* rule;
  };
  std::vector<Case> cases;
  cases.push_back({with_field(s, "spheres/x", changed(s, "spheres/x", 7, nan)),
                   "'spheres/x' value 7", "finite numbers only"});
  cases.push_back(
      {with_field(s, "contacts/shear_force", changed(s, "contacts/shear_force", 4, inf)),
       "'contacts/shear_force' value 4", "finite numbers only"});
  cases.push_back({with_field(s, "cell/h", changed(s, "cell/h", 0, nan)), "'cell/h' value 0",
                   "finite numbers only"});
  cases.push_back({with_field(s, "verlet/h_ref_inv", changed(s, "verlet/h_ref_inv", 8, nan)),
                   "'verlet/h_ref_inv' value 8", "finite numbers only"});
  cases.push_back({with_field(s, "params/numerics/damping", std::vector<double>{nan}),
                   "'params/numerics/damping' value 0", "finite numbers only"});
  cases.push_back(
      {with_field(s, "verlet/skin", std::vector<double>{0.0}), "verlet/*", "the skin must be > 0"});
  cases.push_back({with_field(s, "verlet/skin", std::vector<double>{nan}), "'verlet/skin'",
                   "finite numbers only"});
  cases.push_back({with_field(s, "verlet/r_max", std::vector<double>{0.5 * r_max}), "verlet/*",
                   ">= the largest radius"});
  cases.push_back({with_field(s, "verlet/builds", {-1}), "verlet/*", "builds >= 0"});
  cases.push_back(
      {with_field(s, "verlet/pending", {2}), "'verlet/pending' value 0", "must be 0 or 1"});
  cases.push_back({with_field(s, "spheres/fixed", changed<std::int64_t>(s, "spheres/fixed", 3, 5)),
                   "'spheres/fixed' value 3", "must be 0 or 1"});
  cases.push_back(
      {with_field(s, "contacts/active", changed<std::int64_t>(s, "contacts/active", 2, -1)),
       "'contacts/active' value 2", "must be 0 or 1"});
  {
    std::vector<std::int64_t> pair = s.read_i64("contacts/pair");
    pair[11] = pair[10];  // pair 5 of a sphere with itself
    cases.push_back({with_field(s, "contacts/pair", pair), "'contacts/pair' pair 5",
                     "must be spheres i < j <"});
  }
  cases.push_back({with_field(s, "counters/dt", std::vector<double>{-1e-6}),
                   "'counters/dt' = ", "must be >= 0"});
  for (const Case& c : cases) {
    try {
      (void)dem::Rve::load(c.state);
      ADD_FAILURE() << "loaded a state with " << c.field;
    } catch (const common::InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(c.field), std::string::npos) << m;
      EXPECT_NE(m.find(c.rule), std::string::npos) << m;
    }
  }
  EXPECT_NO_THROW((void)dem::Rve::load(s));  // the unchanged state loads
}
