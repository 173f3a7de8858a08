// Unit tests of farm/grain_views.hpp: which RVEs and steps are drawn, and the series after a
// restart (the views themselves are written through the farm: tests/jobs/grain_views.cmake).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "dem/vtk_export.hpp"
#include "farm/grain_views.hpp"

namespace {

namespace fs = std::filesystem;

const std::vector<std::int64_t> kIds = {0, 1, 2, 5, 9};

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("mpmxdem_grain_views_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "grains");
  return dir;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(GrainViews, OptionsNameTheKeyValueAndRule) {
  farm::GrainViewOptions o;
  EXPECT_NO_THROW(o.validate(kIds));  // no RVEs: off, whatever `every`
  o.rves = {5, 1};
  EXPECT_NO_THROW(o.validate(kIds));
  o.rves = {5, 3};
  try {
    o.validate(kIds);
    FAIL() << "an id that is no point was accepted";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("output.grains.rves = 3: no material point"),
              std::string::npos)
        << e.what();
  }
  o.rves = {5, 5};
  EXPECT_THROW(o.validate(kIds), common::InputError);
  o.rves = {5};
  o.every = 0;
  EXPECT_THROW(o.validate(kIds), common::InputError);
}

TEST(GrainViews, DrawsStepZeroEveryNAndTheLastStepOnce) {
  farm::GrainViewOptions o;
  o.every = 20;
  const farm::GrainViews off(o, kIds, fresh_dir("off").string(), -1, 0.0);
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.due(0));
  EXPECT_FALSE(off.due_at_end(7));
  o.rves = {9, 1};
  const farm::GrainViews v(o, kIds, fresh_dir("on").string(), -1, 0.0);
  EXPECT_TRUE(v.enabled());
  EXPECT_TRUE(v.due(0));
  EXPECT_FALSE(v.due(10));
  EXPECT_TRUE(v.due(40));
  EXPECT_TRUE(v.due_at_end(45));
  EXPECT_TRUE(v.series(1).empty());
  EXPECT_TRUE(v.series(9).empty());
}

TEST(GrainViews, RestartKeepsTheSeriesUpToTheCheckpointAndDropsTheRest) {
  const fs::path dir = fresh_dir("restart");
  const std::vector<dem::VtkSeriesEntry> before = {{0.0, "rve_1_step_0.vtm"},
                                                   {0.25, "rve_1_step_20.vtm"},
                                                   {0.5, "rve_1_step_40.vtm"},
                                                   {0.625, "rve_1_step_50.vtm"}};
  write_text(dir / "grains" / "rve_1.pvd", dem::vtk_series(before));
  write_text(dir / "grains" / "rve_9.pvd", "not a collection");  // damaged: starts anew
  farm::GrainViewOptions o;
  o.rves = {1, 9};
  o.every = 20;
  // Continues the checkpoint of step 40 (t = 0.5 s): the entry of step 50 belonged to the run
  // that went on past that checkpoint.
  const farm::GrainViews v(o, kIds, dir.string(), 40, 0.5);
  ASSERT_EQ(v.series(1).size(), 3U);
  EXPECT_EQ(v.series(1).back().file, "rve_1_step_40.vtm");
  EXPECT_TRUE(v.series(9).empty());
  EXPECT_FALSE(v.due(40));  // drawn before the checkpoint
  EXPECT_TRUE(v.due(60));
  EXPECT_FALSE(v.due_at_end(40));
  // A fresh run into the same directory (--force) starts every series empty.
  const farm::GrainViews fresh(o, kIds, dir.string(), -1, 0.0);
  EXPECT_TRUE(fresh.series(1).empty());
  EXPECT_TRUE(fresh.due(0));
}

}  // namespace
