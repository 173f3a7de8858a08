// dem parameter structs and their tables (dem/params.hpp, dem/rve.hpp): validate() names the real
// job keys, and the defaults (member initializers) lie in their ranges.
#include <gtest/gtest.h>

#include <string>

#include "common/errors.hpp"
#include "dem/params.hpp"
#include "dem/reference_material.hpp"
#include "dem/rve.hpp"

namespace {

template <class S>
std::string error_of(const S& s) {
  try {
    s.validate();
  } catch (const common::InputError& e) {
    return e.what();
  }
  return {};
}

TEST(Params, MaterialErrorsNameTheJobKeys) {
  dem::Material m = dem::reference_material();
  EXPECT_EQ(error_of(m), "");
  m.young = -1.0;
  EXPECT_EQ(error_of(m), "dem.material.young_modulus = -1: must be > 0 Pa");
  m = dem::reference_material();
  m.ks_over_kn = 0.0;
  EXPECT_EQ(error_of(m), "dem.material.stiffness_ratio = 0: must be > 0");
  m = dem::reference_material();
  m.friction_deg = 90.0;
  EXPECT_EQ(error_of(m), "dem.material.friction_angle = 90: must be in [0, 90) deg");
  m = dem::reference_material();
  m.alpha_t = -1.0;
  EXPECT_EQ(error_of(m), "dem.material.twisting.stiffness = -1: must be >= 0");
}

// Every law but CohFrict is described once by dem::for_each_table_law (its table in
// [dem.material.<name>], whose rows are its checkpoint fields too, under distinct keys), so that
// the job's reading, rules, schema and checkpoint cannot miss it; validate() checks the law's own
// table.
TEST(Params, EveryLawButCohFrictHasOneTableLaw) {
  for (const auto& named : dem::kContactLawNames) {
    if (named.value == dem::ContactLawKind::cohfrict) continue;
    int found = 0;
    dem::for_each_table_law([&](const auto& d) {
      if (d.kind != named.value) return;
      ++found;
      EXPECT_EQ(d.section(), "dem.material." + std::string(named.name));
      const auto& rows = d.table.rows;
      for (std::size_t i = 0; i < rows.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
          EXPECT_NE(rows[i].key, rows[j].key) << named.name;
          EXPECT_NE(rows[i].member, rows[j].member) << named.name;
        }
      }
    });
    EXPECT_EQ(found, 1) << named.name;
  }
  dem::Material m = dem::hertz_mindlin_reference_material();
  EXPECT_EQ(error_of(m), "");
  m.hm.poisson = 0.5;
  EXPECT_EQ(error_of(m), "dem.material.hertz_mindlin.poisson_ratio = 0.5: must be in [0, 0.5)");
}

TEST(Params, NumericsErrorsNameTheJobKeysOrTheMember) {
  dem::Numerics n;
  EXPECT_EQ(error_of(n), "");
  n.skin_factor = 0.0;
  EXPECT_EQ(error_of(n), "dem.numerics.verlet_skin = 0: must be in (0, 1]");
  n = {};
  n.dt_safety = 1.5;
  EXPECT_EQ(error_of(n), "dem.numerics.timestep_safety = 1.5: must be in [0.01, 1]");
  n = {};
  n.timestep_update_interval = 0;
  EXPECT_EQ(error_of(n), "dem::Numerics::timestep_update_interval = 0: must be >= 1");
}

TEST(Params, RveParamsErrorsNameTheCouplingKeys) {
  dem::RveParams p;
  p.material = dem::reference_material();
  EXPECT_EQ(error_of(p), "");
  p.p_floor = 0.0;
  EXPECT_EQ(error_of(p), "dem.coupling.pressure_floor = 0: must be > 0 Pa");
  p.p_floor = 1e3;
  p.inertial_number = 0.0;
  EXPECT_EQ(error_of(p), "dem.coupling.inertial_number = 0: must be in [1e-06, 1)");
  p.inertial_number = 1e-3;
  p.max_strain_per_step = 0.0;
  EXPECT_EQ(error_of(p), "dem.coupling.max_strain_per_step = 0: must be in [1e-08, 1)");
  p.max_strain_per_step = 1e-5;
  p.max_steps_per_call = 0;
  EXPECT_EQ(error_of(p), "dem::RveParams::max_steps_per_call = 0: must be >= 1");
  p.max_steps_per_call = 10;
  p.material.density = 0.0;
  EXPECT_EQ(error_of(p), "dem.material.density = 0: must be > 0 kg/m^3");
}

template <class S, std::size_t N>
void expect_defaults_in_range(const common::ParamTable<S, N>& table) {
  for (const auto& row : table) {
    if (row.source == common::Source::job_required) continue;  // a placeholder, no default
    EXPECT_TRUE(row.range.contains(row.default_value())) << table.name(row);
  }
}

TEST(Params, DefaultsLieInTheirRanges) {
  expect_defaults_in_range(dem::kMaterial);
  expect_defaults_in_range(dem::kCohFrict);
  expect_defaults_in_range(dem::kHertzMindlin);
  expect_defaults_in_range(dem::kNumerics);
  expect_defaults_in_range(dem::kRveParams);
}

// The settings jobs validated with (docs/validation/triaxial.md) are the C++ defaults: tests run
// what jobs run.
TEST(Params, DefaultsOfTheDriftedSettings) {
  EXPECT_EQ(dem::Numerics{}.skin_factor, 0.1);
  EXPECT_EQ(dem::RveParams{}.max_strain_per_step, 1e-5);
}

}  // namespace
