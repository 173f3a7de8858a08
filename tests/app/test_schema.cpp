// Tests of the job schema itself: consistent paths, documented keys, no defaults on physics, and
// the dem parameter tables as the one home of their keys.
#include "app/job/schema.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "app/job/job.hpp"
#include "app/job/schema_params.hpp"
#include "app/setup/dem_setup.hpp"
#include "app/setup/insitu.hpp"
#include "app/setup/mpm_setup.hpp"
#include "common/choice_table.hpp"
#include "common/errors.hpp"
#include "common/param_table.hpp"
#include "dem/loading.hpp"
#include "dem/params.hpp"
#include "dem/rve.hpp"
#include "farm/elastic_material.hpp"
#include "farm/mpi_util.hpp"
#include "farm/run_options.hpp"
#include "farm/rve_farm.hpp"
#include "mpm/boundary.hpp"
#include "mpm/friction.hpp"
#include "mpm/solver.hpp"
#include "mpm/solver_choices.hpp"

TEST(Schema, EveryKeyHasADocumentedParentSection) {
  const auto& s = app::job_schema();
  for (const auto& k : s.keys) {
    EXPECT_FALSE(k.doc.empty()) << k.path;
    const std::string parent = app::parent_path(k.path);
    if (parent.empty()) continue;
    const app::Key* p = s.find(parent);
    ASSERT_NE(p, nullptr) << k.path << " has no parent section " << parent;
    EXPECT_TRUE(p->type == app::Type::Table || p->type == app::Type::TableList) << parent;
  }
}

// docs/reference/jobs.md prints each key under the last section added before it, by its last name
// alone: a key added after another section's (mpm.plane_strain after [mpm.regularisation]) would
// read as that section's key.
TEST(Schema, EveryKeyFollowsItsOwnSection) {
  const auto& s = app::job_schema();
  std::string section;  // "" before the first section: the top level
  for (const auto& k : s.keys) {
    if (k.type == app::Type::Table || k.type == app::Type::TableList) {
      section = k.path;
      continue;
    }
    EXPECT_EQ(app::parent_path(k.path), section) << k.path;
  }
}

TEST(Schema, KeysAreUniqueAndDefaultsHaveTheirKeysType) {
  const auto& s = app::job_schema();
  for (std::size_t i = 0; i < s.keys.size(); ++i) {
    for (std::size_t j = i + 1; j < s.keys.size(); ++j) EXPECT_NE(s.keys[i].path, s.keys[j].path);
    const auto& k = s.keys[i];
    EXPECT_FALSE(k.required && k.fallback) << k.path << " is required and has a default";
    if (!k.fallback) continue;
    switch (k.type) {
      case app::Type::Float:
        EXPECT_TRUE(std::holds_alternative<double>(*k.fallback)) << k.path;
        break;
      case app::Type::Int:
        EXPECT_TRUE(std::holds_alternative<std::int64_t>(*k.fallback)) << k.path;
        break;
      case app::Type::String:
        EXPECT_TRUE(std::holds_alternative<std::string>(*k.fallback)) << k.path;
        break;
      default:
        break;
    }
  }
}

TEST(Schema, PhysicalParametersHaveNoDefaults) {
  for (const auto& k : app::job_schema().keys) {
    // The contact law is a choice of model, not a parameter: its default (the CohFrict law) keeps
    // the jobs written before Hertz-Mindlin.
    if (k.path == "dem.material.contact_law") continue;
    if (k.path.starts_with("dem.material.") || k.path.starts_with("mpm.elastic.") ||
        k.path.ends_with(".density") || k.path.ends_with(".pressure")) {
      EXPECT_FALSE(k.fallback.has_value()) << k.path << " is physical and must not have a default";
    }
  }
}

namespace {

// Rows of a dem parameter table are schema keys with the table's rule, unit and default, so a job
// error and the struct's validate() state the same rule for the same key.
// required_when: the table's required rows outside sub-tables are required by a job rule under
// that condition (app::add_params), and say so.
template <class S, std::size_t N>
void expect_rows_in_schema(const common::ParamTable<S, N>& table,
                           const std::string& required_when = {}) {
  const auto& s = app::job_schema();
  for (const auto& row : table) {
    const app::Key* k = s.find(table.name(row));
    if (!row.in_job()) {
      EXPECT_EQ(k, nullptr) << table.name(row) << " is C++ only";
      continue;
    }
    ASSERT_NE(k, nullptr) << table.name(row);
    const bool by_rule = !required_when.empty() && row.source == common::Source::job_required &&
                         row.key.find('.') == std::string_view::npos;
    EXPECT_EQ(k->doc, by_rule ? std::string(row.doc) + " Required " + required_when + "."
                              : std::string(row.doc));
    EXPECT_EQ(app::canonical_unit(k->quantity), common::unit_symbol(row.unit)) << k->path;
    if (row.range.lo || row.range.hi) {
      EXPECT_EQ(app::range_rule(*k), row.range.rule(row.unit)) << k->path;
    }
    EXPECT_EQ(k->required, row.source == common::Source::job_required && !by_rule) << k->path;
    EXPECT_EQ(k->type, row.is_integer() ? app::Type::Int : app::Type::Float) << k->path;
    if (row.source == common::Source::job_optional) {
      EXPECT_FALSE(k->fallback.has_value()) << k->path;
    } else if (by_rule) {
      EXPECT_FALSE(k->fallback.has_value()) << k->path;
    } else if (!k->required) {
      ASSERT_TRUE(k->fallback.has_value()) << k->path;
      if (row.is_integer()) {
        EXPECT_EQ(static_cast<double>(std::get<std::int64_t>(*k->fallback)), row.default_value())
            << k->path;
      } else {
        EXPECT_EQ(std::get<double>(*k->fallback), row.default_value()) << k->path;
      }
    }
  }
}

TEST(Schema, DemTablesAreTheSchemaOfTheirSections) {
  expect_rows_in_schema(dem::kMaterial);
  expect_rows_in_schema(dem::kCohFrict, "with contact_law = \"cohfrict\"");
  expect_rows_in_schema(dem::kHertzMindlin);
  expect_rows_in_schema(dem::kNumerics);
  expect_rows_in_schema(dem::kRveParams);
  expect_rows_in_schema(dem::kPreparation);
  expect_rows_in_schema(dem::kPreparationTarget);
}

TEST(Schema, MpmAndFarmTablesAreTheSchemaOfTheirKeys) {
  expect_rows_in_schema(mpm::kSolverConfig);
  expect_rows_in_schema(farm::kOutputOptions);
  expect_rows_in_schema(farm::kCheckpointOptions);
  expect_rows_in_schema(farm::kBalanceOptions);
}

// [mpm.elastic] is farm::kElasticMaterial: every row is a key of the section with the row's unit,
// range and meaning, and every key of the section is a row.
TEST(Schema, ElasticMaterialTableIsTheSchemaOfItsSection) {
  expect_rows_in_schema(farm::kElasticMaterial);
  const std::string section(farm::kElasticMaterial.section);
  for (const auto& k : app::job_schema().keys) {
    if (app::parent_path(k.path) != section) continue;
    bool row = false;
    for (const auto& r : farm::kElasticMaterial)
      row = row || farm::kElasticMaterial.name(r) == k.path;
    EXPECT_TRUE(row) << k.path << " is no row of farm::kElasticMaterial";
  }
  const app::Key* young = app::job_schema().find("mpm.elastic.young_modulus");
  ASSERT_NE(young, nullptr);
  EXPECT_TRUE(young->required);
  EXPECT_EQ(app::range_rule(*young), "must be > 0 Pa");
  const app::Key* phi = app::job_schema().find("mpm.elastic.friction_angle");
  ASSERT_NE(phi, nullptr);
  EXPECT_FALSE(phi->required);
  EXPECT_FALSE(phi->fallback.has_value());  // absent: linear elastic, no default filled
  EXPECT_EQ(app::range_rule(*phi), "must be in [0, 90) deg");
}

// A choice table's rows are schema keys whose names are the row's and whose default is the
// struct's: a string key out of the names, or a boolean for a flag row; a member initializer
// without a name (plane_strain_axis = -1) makes an optional key.
template <class S, std::size_t N>
void expect_choice_keys(const common::ChoiceTable<S, N>& table) {
  const auto& s = app::job_schema();
  const S defaults{};
  for (const auto& row : table) {
    const std::string key = table.name(row);
    const app::Key* k = s.find(key);
    ASSERT_NE(k, nullptr) << key;
    EXPECT_EQ(k->doc, row.doc) << key;
    if (row.boolean) {
      EXPECT_EQ(k->type, app::Type::Bool) << key;
      EXPECT_TRUE(k->choices.empty()) << key;
      ASSERT_TRUE(k->fallback.has_value()) << key;
      EXPECT_EQ(std::get<bool>(*k->fallback) ? "true" : "false", row.name_in(defaults)) << key;
      continue;
    }
    EXPECT_EQ(k->type, app::Type::String) << key;
    ASSERT_EQ(k->choices.size(), row.count) << key;
    for (std::size_t i = 0; i < row.count; ++i) EXPECT_EQ(k->choices[i], row.names[i]) << key;
    EXPECT_EQ(k->required, row.required) << key;
    ASSERT_EQ(k->fallback.has_value(), row.has_default() && !row.required) << key;
    if (row.has_default() && !row.required) {
      EXPECT_EQ(std::get<std::string>(*k->fallback), row.name_in(defaults)) << key;
    }
  }
}

// The schema of a choice table's keys alone (its sections and sub-tables, no cross-key rules).
template <class S, std::size_t N>
app::Schema choice_schema(const common::ChoiceTable<S, N>& table) {
  app::Schema only_choices;
  const std::string section(table.section);
  for (std::size_t dot = section.find('.'); dot != std::string::npos;
       dot = section.find('.', dot + 1)) {
    only_choices.add(section.substr(0, dot), app::Type::Table, "a parent section");
  }
  only_choices.add(section, app::Type::Table, "the section");
  app::add_choices(only_choices, table);
  for (const auto& row : table) {  // a row in a sub-table of the section (regularisation.average)
    const std::string sub(app::sub_table_of(row.key));
    if (sub.empty() || only_choices.find(section + "." + sub) != nullptr) continue;
    only_choices.add(section + "." + sub, app::Type::Table, "a sub-table");
    app::add_choices(only_choices, table, sub);
  }
  return only_choices;
}

// A job of the table's keys alone sets each name (a flag row: written as a TOML boolean) and
// leaves the other rows at their defaults; an empty section leaves every row at its default.
template <class S, std::size_t N>
void expect_choices_in_schema(const common::ChoiceTable<S, N>& table) {
  expect_choice_keys(table);
  const app::Schema only_choices = choice_schema(table);
  const std::string section(table.section);
  const S defaults{};
  auto filled = [&](const std::string& text) {
    S cfg{};
    app::fill_choices_from_job(app::Job::parse(text, "choice.toml", only_choices, false), table,
                               cfg);
    return cfg;
  };
  const S untouched = filled("[" + section + "]\n");
  for (const auto& row : table) EXPECT_EQ(row.name_in(untouched), row.default_name()) << row.key;
  for (const auto& row : table) {
    for (std::size_t i = 0; i < row.count; ++i) {
      const std::string name(row.names[i]);
      const S cfg = filled("[" + section + "]\n" + std::string(row.key) + " = " +
                           (row.boolean ? name : "\"" + name + "\"") + "\n");
      EXPECT_EQ(row.name_in(cfg), row.names[i]) << row.key;
      for (const auto& other : table) {
        if (other.key != row.key) {
          EXPECT_EQ(other.name_in(cfg), other.name_in(defaults)) << other.key;
        }
      }
    }
  }
}

TEST(Schema, ChoiceTablesAreTheSchemaOfTheirKeysAndFillTheirStructs) {
  expect_choices_in_schema(mpm::kSolverChoices);
  expect_choices_in_schema(dem::kRveChoices);
  expect_choices_in_schema(farm::kFarmChoices);
  expect_choices_in_schema(dem::kMaterialChoices);
}

// A key of an array of tables (mpm.body[].material) whose names are a list beside an enum: the
// schema's allowed values are the list's names, in its order, and a job of that key alone (the
// job schema's own key under its sections) gives back each name's value through choice_of, and
// the fallback where the key is absent.
template <class E, std::size_t N>
void expect_names_of(const std::string& path, const std::array<common::Named<E>, N>& names) {
  const app::Key* key = app::job_schema().find(path);
  ASSERT_NE(key, nullptr) << path;
  std::vector<std::string> want;
  for (const auto& n : names) want.emplace_back(n.name);
  EXPECT_EQ(key->choices, want) << path;

  const std::string array = app::parent_path(path);  // "mpm.body[]"
  const std::string section = app::parent_path(array);
  const std::string table = array.substr(0, array.size() - 2);
  app::Schema only;
  only.add(section, app::Type::Table, "the section");
  only.add(array, app::Type::TableList, "the array of tables");
  only.keys.push_back(*key);
  only.keys.back().required = false;
  const std::string entry = table + "[0]." + app::leaf_name(path);
  for (const auto& n : names) {
    const app::Job job = app::Job::parse(
        "[[" + table + "]]\n" + app::leaf_name(path) + " = \"" + std::string(n.name) + "\"\n",
        "names.toml", only, false);
    EXPECT_EQ(app::choice_of(job, entry, names), n.value) << path << " = " << n.name;
  }
  const app::Job empty = app::Job::parse("[[" + table + "]]\n", "names.toml", only, false);
  EXPECT_EQ(app::choice_of(empty, entry, names, names.back().value), names.back().value) << path;
}

TEST(Schema, KeysOfArraysOfTablesTakeTheNamesOfTheirLists) {
  expect_names_of("mpm.body[].material", app::kBodyMaterialNames);
  expect_names_of("mpm.body[].initial_state", app::kInitialStateNames);
  expect_names_of("mpm.velocity[].face", mpm::kFaceNames);
  expect_names_of("mpm.velocity[].normal", mpm::kFaceNames);
  expect_names_of("mpm.velocity[].contact", mpm::kWallContactNames);
  expect_names_of("mpm.traction[].face", mpm::kFaceNames);
  // Every other key of an array of tables with names is one of the above, or it would have them
  // written out of its list.
  const std::vector<std::string> listed = {"mpm.body[].material",    "mpm.body[].initial_state",
                                           "mpm.velocity[].face",    "mpm.velocity[].normal",
                                           "mpm.velocity[].contact", "mpm.traction[].face"};
  for (const auto& k : app::job_schema().keys) {
    if (k.choices.empty() || k.path.find("[]") == std::string::npos) continue;
    EXPECT_NE(std::find(listed.begin(), listed.end(), k.path), listed.end()) << k.path;
  }
  // A face's name is its axis and side.
  for (const auto& n : mpm::kFaceNames) {
    EXPECT_EQ(mpm::axis_of(n.value), n.name[0] - 'x') << n.name;
    EXPECT_EQ(mpm::side_of(n.value), n.name[1] == '-' ? -1 : 1) << n.name;
  }
}

// The other [mpm] keys that are no table rows keep the struct's defaults too, and the names the
// mpm module prints are the table's.
TEST(Schema, MpmKeysOutsideTheTablesHaveTheSolverConfigDefaults) {
  const auto& s = app::job_schema();
  const mpm::SolverConfig defaults;
  EXPECT_EQ(mpm::kSolverChoices.row("shape_function")->name_in(defaults),
            mpm::to_string(defaults.shape));
  EXPECT_EQ(s.find("mpm.gravity")->fallback.has_value(), false);
  EXPECT_TRUE(defaults.gravity.isZero());
  EXPECT_EQ(farm::wait_mode_from(std::get<std::string>(*s.find("farm.wait")->fallback)),
            farm::FarmOptions{}.wait);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const common::InputError& e) {
    return e.what();
  }
  return {};
}

// dem.loading.type is a required choice row (no default): the schema requires the key, its names
// are the row's and each sets its value; absent, the job names the key.
TEST(Schema, TheLoadingTypeIsARequiredChoiceRow) {
  expect_choice_keys(dem::kLoadingChoices);
  const app::Schema only = choice_schema(dem::kLoadingChoices);
  for (const auto& named : dem::kLoadingTypeNames) {
    dem::LoadingProgramme l;
    l.type = named.value == dem::LoadingType::triaxial ? dem::LoadingType::isotropic
                                                       : dem::LoadingType::triaxial;
    app::fill_choices_from_job(
        app::Job::parse("[dem]\n[dem.loading]\ntype = \"" + std::string(named.name) + "\"\n",
                        "loading.toml", only, false),
        dem::kLoadingChoices, l);
    EXPECT_EQ(l.type, named.value) << named.name;
  }
  const std::string missing = error_of(
      [&] { (void)app::Job::parse("[dem]\n[dem.loading]\n", "loading.toml", only, false); });
  EXPECT_NE(missing.find("dem.loading.type"), std::string::npos) << missing;
}

// The structs' validate() name the job keys, with the rule the job errors state.
TEST(Schema, MpmAndFarmValidationNamesTheJobKeys) {
  mpm::SolverConfig cfg;
  cfg.grid = {common::Vec3::Zero(), common::Vec3::Ones(), common::Vec3i::Ones()};
  EXPECT_EQ(error_of([&] { cfg.validate(); }), "");
  cfg.flip = 1.5;
  EXPECT_EQ(error_of([&] { cfg.validate(); }), "mpm.flip = 1.5: must be in [0, 1]");
  cfg.flip = 1.0;
  cfg.mass_threshold = 0.0;
  EXPECT_EQ(error_of([&] { cfg.validate(); }), "mpm.mass_threshold = 0: must be in (0, 1)");
  cfg.mass_threshold = 1e-6;
  cfg.max_volume_ratio = 1.0;
  EXPECT_EQ(error_of([&] { cfg.validate(); }),
            "mpm::SolverConfig::max_volume_ratio = 1: must be > 1");

  farm::BalanceOptions b;
  b.threshold = 0.5;
  EXPECT_EQ(error_of([&] { common::check_ranges(farm::kBalanceOptions, b); }),
            "farm.rebalance_threshold = 0.5: must be >= 1");
  farm::OutputOptions o;
  o.every = 0;
  EXPECT_EQ(error_of([&] { common::check_ranges(farm::kOutputOptions, o); }),
            "output.every = 0: must be >= 1");
  farm::CheckpointOptions c;
  c.keep = 0;
  EXPECT_EQ(error_of([&] { common::check_ranges(farm::kCheckpointOptions, c); }),
            "output.checkpoint_keep = 0: must be >= 1");
}

const char* kDemJob = R"([dem.material]
density = "2650 kg/m^3"
young_modulus = "300 MPa"
stiffness_ratio = 0.5
friction_angle = "0.5 rad"
rolling_stiffness = 2.0
rolling_strength = 0.3
[dem.material.twisting]
stiffness = 1.5
strength = -1.0
[dem.sample]
spheres = 60
psd_diameters = ["130 um", "270 um"]
psd_passing = [0.0, 1.0]
[dem.preparation]
pressure = "100 kPa"
friction_angle = "10 deg"
[dem.numerics]
verlet_skin = 0.25
[dem.loading]
type = "isotropic"
inertial_number = 1e-3
confining_pressure = "200 kPa"
)";

TEST(Schema, JobValuesFillTheDemStructsAndAbsentKeysTakeTheStructDefaults) {
  const app::Job job = app::Job::parse(kDemJob, "dem.toml");
  const dem::Material m = app::dem_material(job);
  EXPECT_EQ(m.density, 2650.0);
  EXPECT_EQ(m.young, 3e8);
  EXPECT_EQ(m.ks_over_kn, 0.5);
  EXPECT_NEAR(m.friction_deg, 28.647889756541161, 1e-12);
  EXPECT_EQ(m.alpha_r, 2.0);
  EXPECT_EQ(m.eta_r, 0.3);
  EXPECT_EQ(m.alpha_t, 1.5);
  EXPECT_EQ(m.eta_t, -1.0);
  const dem::Numerics n = app::dem_numerics(job);
  EXPECT_EQ(n.skin_factor, 0.25);
  EXPECT_EQ(n.damping, dem::Numerics{}.damping);
  EXPECT_EQ(n.dt_safety, dem::Numerics{}.dt_safety);
  EXPECT_EQ(n.timestep_update_interval, dem::Numerics{}.timestep_update_interval);
  const dem::Preparation p = app::dem_preparation(job);
  EXPECT_EQ(p.friction_comp_deg, 10.0);
  EXPECT_EQ(p.target.pressure, 1e5);
  EXPECT_EQ(p.target.stress_tol, dem::EquilibriumTarget{}.stress_tol);
  EXPECT_EQ(p.target.unbalanced_tol, dem::EquilibriumTarget{}.unbalanced_tol);
  EXPECT_EQ(p.target.check_every, dem::EquilibriumTarget{}.check_every);
}

// Integer keys reach their members exactly, up to 2^63 - 1 (through a double every integer key
// at 2^63 - 1 was refused as "= -9223372036854775808: must be >= 1", without file or line).
TEST(Schema, IntegerKeysFillTheirMembersExactly) {
  const std::string text = std::string(kDemJob) +
                           "[dem.coupling]\ninertial_number = 1e-3\n"
                           "dt_refresh = 9223372036854775807\n"
                           "max_strain_per_step = 1e-5\n";
  const app::Job job = app::Job::parse(text, "dem.toml");
  dem::RveParams p;
  app::fill_from_job(job, dem::kRveParams, p);
  EXPECT_EQ(p.dt_refresh, std::numeric_limits<std::int64_t>::max());
  EXPECT_NO_THROW(common::check_ranges(dem::kRveParams, p));
  const app::Job odd = app::Job::parse(std::string(kDemJob) +
                                           "[dem.coupling]\ninertial_number = 1e-3\n"
                                           "dt_refresh = 9007199254740993\n",  // 2^53 + 1
                                       "dem.toml");
  app::fill_from_job(odd, dem::kRveParams, p);
  EXPECT_EQ(p.dt_refresh, (std::int64_t{1} << 53) + 1);
}

}  // namespace
