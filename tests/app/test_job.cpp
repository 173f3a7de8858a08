// Tests of app::Job: validation messages, defaults, cross-key rules, resolved output.
#include "app/job/job.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include "common/errors.hpp"

namespace {

const char* kDemJob = R"(title = "t"
[dem.material]
density = "2650 kg/m^3"
young_modulus = 3e8
stiffness_ratio = 0.5
friction_angle = 30
rolling_stiffness = 2.0
rolling_strength = 0.3

[dem.sample]
spheres = 100
psd_diameters = ["130 um", "270 um"]
psd_passing = [0.0, 1.0]

[dem.preparation]
pressure = "100 kPa"
friction_angle = 1.0
)";

std::string error_of(const std::string& text) {
  try {
    (void)app::Job::parse(text, "job.toml");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string replace(std::string s, const std::string& a, const std::string& b) {
  const auto pos = s.find(a);
  EXPECT_NE(pos, std::string::npos) << a;
  return s.replace(pos, a.size(), b);
}

}  // namespace

TEST(Job, ResolvesValuesInCanonicalUnitsAndFillsDefaults) {
  const auto job = app::Job::parse(kDemJob, "job.toml");
  EXPECT_DOUBLE_EQ(job.number("dem.material.density"), 2650.0);
  EXPECT_DOUBLE_EQ(job.number("dem.material.friction_angle"),
                   30.0);  // an int where a number is asked
  EXPECT_DOUBLE_EQ(job.numbers("dem.sample.psd_diameters")[1], 270e-6);
  EXPECT_EQ(job.integer("dem.sample.spheres"), 100);
  EXPECT_DOUBLE_EQ(job.number("dem.numerics.damping"), 0.2);  // default of an absent section
  EXPECT_TRUE(job.entries().at("dem.numerics.damping").defaulted);
  EXPECT_FALSE(job.has("dem.material.twisting.stiffness"));  // optional physics stays off
  EXPECT_FALSE(job.has_section("mpm"));
}

TEST(Job, ResolvedTomlParsesBackToTheSameValues) {
  const auto job = app::Job::parse(kDemJob, "job.toml");
  const auto again = app::Job::parse(job.resolved_toml(), "resolved.toml");
  ASSERT_EQ(job.entries().size(), again.entries().size());
  for (const auto& [path, e] : job.entries()) {
    ASSERT_TRUE(again.has(path)) << path;
    EXPECT_EQ(e.value, again.entries().at(path).value) << path;
  }
}

// Every shipped job's job.resolved.toml (what a run writes, defaults included) is itself a job that
// validates, with the same values: a user re-runs a run's resolved job as it is.
TEST(Job, EveryShippedJobsResolvedTomlIsAValidJob) {
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(MPMXDEM_SOURCE_DIR "/jobs")) {
    if (f.path().extension() != ".toml") continue;
    const auto job = app::Job::load(f.path().string());
    const std::string beside = (f.path().parent_path() / "resolved.toml").string();
    std::optional<app::Job> again;
    ASSERT_NO_THROW(again.emplace(app::Job::parse(job.resolved_toml(), beside))) << f.path();
    ASSERT_EQ(job.entries().size(), again->entries().size()) << f.path();
    for (const auto& [path, e] : job.entries()) {
      ASSERT_TRUE(again->has(path)) << f.path() << ": " << path;
      EXPECT_EQ(e.value, again->entries().at(path).value) << f.path() << ": " << path;
    }
    ++n;
  }
  EXPECT_GE(n, 20);
}

TEST(Job, ReportsEveryErrorWithFileLineKeyValueAndRule) {
  std::string text = replace(kDemJob, "friction_angle = 30", "friction_angle = 95");
  text = replace(text, "spheres = 100", "spheres = 1.5");
  const std::string err = error_of(text);
  EXPECT_NE(err.find("job.toml:6: dem.material.friction_angle = 95: must be in [0, 90) deg "
                     "[Inter-particle friction angle phi. [deg]]"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("job.toml:11: dem.sample.spheres = 1.5: must be an integer"),
            std::string::npos)
      << err;
}

TEST(Job, UnknownKeySuggestsTheClosestOne) {
  const std::string err = error_of(replace(kDemJob, "rolling_strength", "roling_strength"));
  EXPECT_NE(err.find("job.toml:8: dem.material.roling_strength: unknown key; did you mean "
                     "'rolling_strength'?"),
            std::string::npos)
      << err;
}

TEST(Job, CrossKeyRulesNameBothKeys) {
  const std::string err =
      error_of(replace(kDemJob, "psd_passing = [0.0, 1.0]", "psd_passing = [0.2, 1.0]"));
  EXPECT_NE(
      err.find("job.toml:13: dem.sample.psd_passing = [0.2, 1.0]: must start at 0 and end at 1"),
      std::string::npos)
      << err;
  const std::string err2 = error_of(replace(kDemJob, "spheres = 100\n", ""));
  EXPECT_NE(
      err2.find(
          "job.toml:10: dem.sample.spheres is missing: required when no packing file is given"),
      std::string::npos)
      << err2;
}

// The adaptive skin's range: its thinnest skin must not exceed its widest (verlet_skin, given or
// default).
TEST(Job, AdaptiveSkinRangeIsChecked) {
  const std::string base = std::string(kDemJob) + "\n[dem.numerics]\nverlet_skin_min = 0.2\n";
  const std::string err = error_of(base);
  EXPECT_NE(err.find("job.toml:20: dem.numerics.verlet_skin_min = 0.2: must be <= "
                     "dem.numerics.verlet_skin (0.1)"),
            std::string::npos)
      << err;
  EXPECT_EQ(error_of(base + "verlet_skin = 0.25\n"), "(no error)");
  EXPECT_NE(error_of(base + "verlet_skin = 0.15\n").find("(0.15)"), std::string::npos);
}

TEST(Job, OptionalPhysicsNeedsAllItsParametersOnceSwitchedOn) {
  std::string text = kDemJob;
  text += "\n[dem.material.twisting]\nstiffness = 0.5\n";
  const std::string err = error_of(text);
  EXPECT_NE(err.find("dem.material.twisting.strength is missing: required"), std::string::npos)
      << err;
}

// The keys of a contact law are required with it and refused with another, each error naming the
// file, the line, the key and the law; a complete Hertz-Mindlin material is valid.
TEST(Job, ContactLawKeysAreRequiredWithTheLawAndRefusedWithAnother) {
  // The CohFrict law (the default) without one of its keys.
  const std::string err = error_of(replace(kDemJob, "stiffness_ratio = 0.5\n", ""));
  EXPECT_NE(err.find("dem.material.stiffness_ratio is missing: required with "
                     "dem.material.contact_law = \"cohfrict\""),
            std::string::npos)
      << err;
  // Hertz-Mindlin: the CohFrict keys are refused, its own table is required.
  const std::string hm =
      replace(kDemJob, "[dem.material]\n", "[dem.material]\ncontact_law = \"hertz_mindlin\"\n");
  const std::string err2 = error_of(hm);
  EXPECT_NE(err2.find("job.toml:6: dem.material.stiffness_ratio = 0.5: not used with "
                      "dem.material.contact_law = \"hertz_mindlin\": remove it or change the law"),
            std::string::npos)
      << err2;
  EXPECT_NE(err2.find("job.toml:3: dem.material.contact_law = \"hertz_mindlin\": needs the table "
                      "[dem.material.hertz_mindlin] (poisson_ratio, rolling_stiffness, "
                      "rolling_strength, twisting_stiffness)"),
            std::string::npos)
      << err2;
  std::string ok = hm;
  for (const char* k :
       {"stiffness_ratio = 0.5\n", "rolling_stiffness = 2.0\n", "rolling_strength = 0.3\n"}) {
    ok = replace(ok, k, "");
  }
  const std::string table =
      "\n[dem.material.hertz_mindlin]\npoisson_ratio = 0.25\nrolling_stiffness = \"2e-5 N m/rad\"\n"
      "rolling_strength = 0.3\ntwisting_stiffness = 0.0\n";
  EXPECT_EQ(error_of(ok + table), "(no error)");
  // Its table with a missing key, an out-of-range value, the wrong unit.
  EXPECT_NE(error_of(ok + replace(table, "twisting_stiffness = 0.0\n", ""))
                .find("dem.material.hertz_mindlin.twisting_stiffness is missing: required"),
            std::string::npos);
  EXPECT_NE(error_of(ok + replace(table, "poisson_ratio = 0.25", "poisson_ratio = 0.5"))
                .find("dem.material.hertz_mindlin.poisson_ratio = 0.5: must be in [0, 0.5)"),
            std::string::npos);
  EXPECT_NE(error_of(ok + replace(table, "\"2e-5 N m/rad\"", "\"2e-5 Pa\""))
                .find("dem.material.hertz_mindlin.rolling_stiffness"),
            std::string::npos);
  // The Hertz-Mindlin table with the CohFrict law is refused.
  EXPECT_NE(error_of(std::string(kDemJob) + table)
                .find("job.toml:19: [dem.material.hertz_mindlin]: not used with "
                      "dem.material.contact_law = \"cohfrict\""),
            std::string::npos);
  // An unknown law names the ones there are.
  EXPECT_NE(error_of(replace(hm, "hertz_mindlin", "hertz")).find("hertz_mindlin"),
            std::string::npos);
}

TEST(Job, MissingFileIsAnInputError) {
  EXPECT_THROW((void)app::Job::load("/nonexistent/job.toml"), common::InputError);
}

TEST(EditDistance, Basics) {
  EXPECT_EQ(app::edit_distance("", "abc"), 3u);
  EXPECT_EQ(app::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(app::edit_distance("same", "same"), 0u);
}

TEST(Job, AnInvalidRequiredValueIsReportedOnceNotAlsoAsMissing) {
  const std::string e =
      error_of(replace(kDemJob, "friction_angle = 30", "friction_angle = \"95 deg\""));
  EXPECT_NE(e.find("job.toml:6: dem.material.friction_angle = \"95 deg\": must be in [0, 90)"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find("is missing"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one error only:\n" << e;
}

TEST(Job, SuggestionsPreferTheSameWordsOverShortSubstrings) {
  // "endtime" holds "dt" but is "end_time" without its underscore.
  const std::string mpm = R"([mpm]
endtime = "1 s"
[mpm.grid]
origin = [0, 0, 0]
spacing = [1, 1, 1]
cells = [1, 1, 1]
)";
  const std::string e = error_of(mpm);
  EXPECT_NE(e.find("mpm.endtime: unknown key; did you mean 'end_time'?"), std::string::npos) << e;
  EXPECT_NE(error_of(replace(kDemJob, "young_modulus", "Young_Modulus"))
                .find("did you mean 'young_modulus'?"),
            std::string::npos);
}

TEST(Job, AHugeUnknownKeyIsNotEchoedWhole) {
  const std::string key(100000, 'k');
  const std::string e = error_of(replace(kDemJob, "density = ", key + " = 1\ndensity = "));
  EXPECT_NE(e.find("kkk...: unknown key"), std::string::npos) << e.substr(0, 300);
  EXPECT_LT(e.size(), 2000u);
}

TEST(Job, AHugePackingPathIsNotEchoedWhole) {
  std::string text = replace(kDemJob, "spheres = 100\n", "");
  text = replace(text, "psd_diameters = [\"130 um\", \"270 um\"]\n", "");
  text = replace(text, "psd_passing = [0.0, 1.0]\n",
                 "packing = \"" + std::string(100000, 'p') + "\"\n");
  const std::string e = error_of(text);
  EXPECT_NE(e.find("no such file 'ppp"), std::string::npos) << e.substr(0, 300);
  EXPECT_LT(e.size(), 1000u);
}
