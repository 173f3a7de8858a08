// Tests of app/restart_check: which keys a restart may change, and the messages of a refusal.
#include "app/run/restart_check.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/errors.hpp"

namespace {

const char* kJob = R"(title = "t"
[mpm]
end_time = "1 s"
[mpm.grid]
origin = [0, 0, 0]
spacing = [1, 1, 1]
cells = [1, 1, 1]
[[mpm.body]]
min = [0, 0, 0]
max = [1, 1, 1]
points_per_cell = 2
density = 1000
material = "elastic"
[mpm.elastic]
young_modulus = "50 MPa"
poisson_ratio = 0.3
[[mpm.velocity]]
face = "z-"
z = 0.0
)";

std::string replaced(std::string s, const std::string& a, const std::string& b) {
  const auto pos = s.find(a);
  EXPECT_NE(pos, std::string::npos) << a;
  return s.replace(pos, a.size(), b);
}

app::Job job(const std::string& text) { return app::Job::parse(text, "job.toml"); }

std::string refusal(const std::string& checkpoint_job, const std::string& new_job,
                    const std::filesystem::path& out) {
  try {
    app::check_restart(job(new_job), "ckpt.h5", checkpoint_job, out);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

std::filesystem::path empty_dir(const std::string& name) {
  const auto dir = std::filesystem::path(testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(RestartCheck, RunControlKeysMayChangePhysicsMayNot) {
  EXPECT_TRUE(app::restart_may_change("mpm.end_time"));
  EXPECT_TRUE(app::restart_may_change("output.every"));
  EXPECT_TRUE(app::restart_may_change("farm.rebalance_threshold"));
  EXPECT_TRUE(app::restart_may_change("title"));
  EXPECT_FALSE(app::restart_may_change("mpm.elastic.young_modulus"));
  EXPECT_FALSE(app::restart_may_change("mpm.dt"));
  EXPECT_FALSE(app::restart_may_change("dem.material.friction_angle"));
}

TEST(RestartCheck, ChangedPhysicalKeysAreNamedWithBothValues) {
  const std::string changed = replaced(replaced(kJob, "\"50 MPa\"", "\"60 MPa\""),
                                       "points_per_cell = 2", "points_per_cell = 1");
  const std::string e = refusal(kJob, changed, empty_dir("restart_check_a"));
  EXPECT_NE(e.find("cannot restart from ckpt.h5"), std::string::npos) << e;
  EXPECT_NE(e.find("2 key(s)"), std::string::npos) << e;
  EXPECT_NE(e.find("mpm.body[0].points_per_cell = 2 -> 1"), std::string::npos) << e;
  EXPECT_NE(e.find("mpm.elastic.young_modulus = 50000000.0 -> 60000000.0"), std::string::npos) << e;
  // A key given in one job only (a default in the other counts as given).
  const std::string e2 =
      refusal(kJob, replaced(kJob, "end_time = \"1 s\"", "end_time = \"1 s\"\ndt = 0.001"),
              empty_dir("restart_check_b"));
  EXPECT_NE(e2.find("mpm.dt = (absent) -> 0.001"), std::string::npos) << e2;
}

TEST(RestartCheck, EndTimeTitleAndOutputsMayChange) {
  std::string later = replaced(kJob, "end_time = \"1 s\"", "end_time = \"5 s\"");
  later = replaced(later, "title = \"t\"",
                   "title = \"u\"\n[output]\nevery = 3\n[farm]\nwait = \"spin\"");
  EXPECT_EQ(refusal(kJob, later, empty_dir("restart_check_c")), "");
}

TEST(RestartCheck, ADirectoryOfAnotherRunIsRefused) {
  const auto dir = empty_dir("restart_check_d");
  std::ofstream(dir / "job.toml") << replaced(kJob, "points_per_cell = 2", "points_per_cell = 1");
  const std::string e = refusal(kJob, kJob, dir);
  EXPECT_NE(e.find("holds the results of another run"), std::string::npos) << e;
  EXPECT_NE(e.find("mpm.body[0].points_per_cell = 2 -> 1"), std::string::npos) << e;
  std::filesystem::remove(dir / "job.toml");
  std::ofstream(dir / "results.h5") << "x";
  EXPECT_NE(refusal(kJob, kJob, dir).find("holds results.h5 but no job.toml"), std::string::npos);
  std::ofstream(dir / "job.toml") << kJob;
  EXPECT_EQ(refusal(kJob, kJob, dir), "");
}
