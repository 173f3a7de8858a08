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
#include "former_state.hpp"

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

// Each parameter is a field named by its job key (a C++-only one by its member), holding the
// member: the names written out here, not taken from the code's own tables.
TEST(State, ParametersAreNamedScalarFields) {
  const dem::Rve rve = distinct_rve();
  common::StateStore s;
  rve.save(s);
  const dem::RveParams& p = rve.params();
  const std::vector<std::pair<const char*, double>> expected{
      {"params/material/density", p.material.density},
      {"params/material/young_modulus", p.material.young},
      {"params/material/stiffness_ratio", p.material.ks_over_kn},
      {"params/material/friction_angle", p.material.friction_deg},
      {"params/material/rolling_stiffness", p.material.alpha_r},
      {"params/material/rolling_strength", p.material.eta_r},
      {"params/material/twisting/stiffness", p.material.alpha_t},
      {"params/material/twisting/strength", p.material.eta_t},
      {"params/numerics/damping", p.numerics.damping},
      {"params/numerics/timestep_safety", p.numerics.dt_safety},
      {"params/numerics/verlet_skin", p.numerics.skin_factor},
      {"params/numerics/verlet_skin_min", p.numerics.skin_min_factor},
      {"params/numerics/max_skew", p.numerics.max_skew},
      {"rve/params/inertial_number", p.inertial_number},
      {"rve/params/d50", p.d50},
      {"rve/params/pressure_floor", p.p_floor},
      {"rve/params/max_strain_per_step", p.max_strain_per_step},
      {"rve/params/disconnect_fraction", p.disconnect_fraction},
      {"rve/params/initial_pressure", p.initial_pressure},
      {"rve/d50_used", rve.d50()},
      {"verlet/skin", rve.simulation().verlet().skin},
      {"counters/dt", rve.simulation().dt()},
  };
  for (const auto& [name, value] : expected) {
    EXPECT_EQ(s.read_f64(name), std::vector<double>{value}) << name;
  }
  // Integers, and the choices as the index of their name (cohfrict; carried, material,
  // disconnected, stepped: the order of the names in docs/reference/jobs.md).
  const std::vector<std::pair<const char*, std::int64_t>> integers{
      {"params/numerics/timestep_update_interval", 77},
      {"rve/params/max_steps_per_call", 5000},
      {"rve/params/dt_refresh", p.dt_refresh},
      {"rve/params/min_dem_steps", p.min_dem_steps},
      {"params/material/contact_law", 0},
      {"rve/params/end_forces", 1},
      {"rve/params/rate", 0},
      {"rve/params/contact_loss", 0},
      {"rve/params/free_flight", 0},
      {"verlet/built_at_step", rve.simulation().verlet().built_at_step},
      {"verlet/shell_pairs", rve.simulation().verlet().shell_pairs},
      {"dem/version", 5},
  };
  for (const auto& [name, value] : integers) {
    EXPECT_EQ(s.read_i64(name), std::vector<std::int64_t>{value}) << name;
  }
  EXPECT_EQ(dem::kStateVersion, 5);
  EXPECT_GT(rve.simulation().verlet().shell_pairs, 0);
  for (const char* old :
       {"params/material", "params/numerics", "rve/params", "contacts/props", "verlet/skin_rmax",
        "counters/time_dt", "params/material/young", "params/material/alpha_t",
        "params/numerics/dt_safety", "params/numerics/skin_factor", "rve/p_floor", "rve/rate",
        "rve/carry_end_forces", "rve/inertial_number"}) {
    EXPECT_FALSE(s.has(old)) << old;
  }
  // Loading gives back the same parameters, member by member.
  const dem::Rve back = dem::Rve::load(s);
  common::StateStore again;
  back.save(again);
  EXPECT_TRUE(again.fields() == s.fields());
}

// Versions 2 to 4 wrote the parameters under the C++ members' names (params/material/young,
// rve/p_floor) and the choices as flags (rve/rate 1: material): such a state reads back the same
// parameters and continues bit for bit, written again as version 5.
TEST(State, Version3IsReadUnderTheFormerNames) {
  dem::RveParams p = distinct_rve().params();
  p.dt_refresh = 3;
  p.min_dem_steps = 2;
  p.disconnect_fraction = 0.45;
  p.rate = dem::RveRate::coupling;
  p.contact_loss = dem::ContactLoss::disconnected;
  p.carry_end_forces = false;
  p.free_flight = true;
  dem::Rve a(dem_test::reference_packing(), p);
  common::StateStore v5;
  a.save(v5);
  const common::StateStore v3 = dem_test::as_former_version(v5, 3);
  ASSERT_TRUE(v3.has("params/material/young"));
  ASSERT_TRUE(v3.has("rve/p_floor"));
  ASSERT_FALSE(v3.has("params/material/young_modulus"));
  EXPECT_EQ(v3.read_i64("rve/rate"), std::vector<std::int64_t>{0});  // then: 0 was coupling
  dem::Rve b = dem::Rve::load(v3);
  common::StateStore again;
  b.save(again);
  EXPECT_TRUE(again.fields() == v5.fields());
  common::Mat3 l = common::Mat3::Zero();
  l(2, 2) = -1.0;
  l(0, 1) = 0.5;
  for (int k = 0; k < 3; ++k) ASSERT_EQ(a.step(l, 1e-6).dem_steps, b.step(l, 1e-6).dem_steps);
  common::StateStore sa;
  common::StateStore sb;
  a.save(sa);
  b.save(sb);
  EXPECT_TRUE(sa.fields() == sb.fields());
  // A field of then missing is named by its name of then.
  common::StateStore missing;
  for (const auto& [n, f] : v3.fields()) {
    if (n == "params/material/friction_deg") continue;
    std::visit([&](const auto& v) { missing.write(n, std::span(v.data(), v.size())); }, f);
  }
  try {
    (void)dem::Rve::load(missing);
    ADD_FAILURE() << "a state without its friction angle was read";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("params/material/friction_deg"), std::string::npos)
        << e.what();
  }
}

// The standalone sample's time-step interval was written as params/numerics/dt_refresh before the
// RVEs' own dt_refresh took that name alone: a state of then is read with its value.
TEST(State, TheTimestepIntervalIsReadUnderItsFormerName) {
  const dem::Rve rve = distinct_rve();
  common::StateStore s;
  rve.save(s);
  common::StateStore before;
  const common::StateStore v3 = dem_test::as_former_version(s, 3);
  for (const auto& [n, f] : v3.fields()) {
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
           {"'dem/version' = 1", "reads versions 2 to 5 only", "params/material"}) {
        EXPECT_NE(m.find(needle), std::string::npos) << m;
      }
    }
  }
  // A version this build does not know is refused by it, never read as another.
  try {
    (void)dem::Rve::load(with_field(s, "dem/version", {6}));
    ADD_FAILURE() << "a version-6 state was loaded";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'dem/version' = 6: this build reads versions 2 to 5"),
              std::string::npos)
        << e.what();
  }
}

// Version 2 stored every contact property and the normal force per pair; version 3 only tan_phi
// (the others follow from the radii, the normal force from the branch). A version-2 state (here:
// a version-3 one given the seven fields, their values scrambled: they are not read) loads and
// continues with the same bits as the version-3 one.
TEST(State, Version2IsReadAndContinuesAsVersion3) {
  const dem::Rve rve = distinct_rve();
  common::StateStore v5;
  rve.save(v5);
  const common::StateStore v3 = dem_test::as_former_version(v5, 3);
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

// A Hertz-Mindlin state carries the law (the index of its name) and its parameters under their
// job keys, and continues bit for bit after a load; a state naming another law is refused, naming
// the field. A version-4 state (the law's enumerator, its C++ members' names) reads the same.
TEST(State, HertzMindlinStateContinuesBitForBitAndVersion4IsRead) {
  dem::Material m = dem::hertz_mindlin_reference_material();
  m.hm.ktwist = 2e-5;
  dem::Simulation a = dem::make_simulation(dem_test::hertz_mindlin_packing(), m, dem::Numerics{});
  a.cell().l(2, 2) = -5.0;  // compress, so that contacts slide, roll and twist
  a.refresh_dt();
  for (int k = 0; k < 100; ++k) a.step();
  common::StateStore s;
  dem::save_simulation(a, s);
  EXPECT_EQ(s.read_i64("dem/version"), std::vector<std::int64_t>{5});
  EXPECT_EQ(s.read_i64("params/material/contact_law"), std::vector<std::int64_t>{1});
  EXPECT_EQ(s.read_f64("params/material/hertz_mindlin/poisson_ratio"),
            std::vector<double>{m.hm.poisson});
  EXPECT_EQ(s.read_f64("params/material/hertz_mindlin/rolling_stiffness"),
            std::vector<double>{1e-4});
  EXPECT_EQ(s.read_f64("params/material/hertz_mindlin/twisting_stiffness"),
            std::vector<double>{2e-5});
  EXPECT_EQ(s.read_f64("params/material/hertz_mindlin/rolling_strength"),
            std::vector<double>{m.hm.eta});
  EXPECT_FALSE(s.has("params/material/hertz_mindlin/krot"));
  dem::Simulation b = dem::load_simulation(s);
  EXPECT_EQ(b.law().kind(), dem::ContactLawKind::hertz_mindlin);
  const common::StateStore v4 = dem_test::as_former_version(s, 4);
  ASSERT_TRUE(v4.has("params/material/hertz_mindlin/krot"));
  dem::Simulation c = dem::load_simulation(v4);
  EXPECT_EQ(c.law().kind(), dem::ContactLawKind::hertz_mindlin);
  common::StateStore sc;
  dem::save_simulation(c, sc);
  EXPECT_TRUE(sc.fields() == s.fields());
  (void)continue_both(a, b, 200);
  dem::Simulation d = dem::load_simulation(s);
  (void)continue_both(c, d, 50);
  for (const auto& [state, name] :
       {std::pair{s,
                  "'params/material/contact_law' = 7: must be one of 0 (cohfrict), 1 "
                  "(hertz_mindlin)"},
        std::pair{v4,
                  "'params/material/contact_law' = 7: must be one of 1 (hertz_mindlin) in "
                  "a version 4 state"}}) {
    try {
      (void)dem::load_simulation(with_field(state, "params/material/contact_law", {7}));
      ADD_FAILURE() << "a state of an unknown law was read";
    } catch (const common::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
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
  cases.push_back({with_field(s, "rve/params/pressure_floor", std::vector<double>{inf}),
                   "'rve/params/pressure_floor' value 0", "finite numbers only"});
  cases.push_back({with_field(s, "rve/params/rate", {2}), "'rve/params/rate' = 2",
                   "must be one of 0 (material), 1 (coupling)"});
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
