// run_summary.json (app/run/run_summary.hpp): how a run segment ended, and its fields as JSON.
#include "app/run/run_summary.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <limits>
#include <string>

#include "app/run/wall_budget.hpp"

namespace {

app::RunRecord finished(std::int64_t steps, double time) {
  app::RunRecord r;
  r.job = "jobs/a.toml";
  r.end_time = 1.0;
  farm::RunSummary s;
  s.steps = steps;
  s.time = time;
  s.wall_s = 2.5;
  s.dem_steps = 400;
  s.rve_steps = 100;
  s.checkpoints = {"out/checkpoint_0000000010.h5"};
  r.summary = s;
  return r;
}

bool has(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(RunSummary, NamesHowTheSegmentEnded) {
  app::RunRecord r = finished(10, 1.0);
  EXPECT_EQ(app::run_end(r), "end_time");
  r.max_steps = 10;
  EXPECT_EQ(app::run_end(r), "end_time");  // the end time reached at the last allowed step
  r.summary->time = 0.5;
  EXPECT_EQ(app::run_end(r), "max_steps");
  r.summary->stopped_by = SIGTERM;
  EXPECT_EQ(app::run_end(r), "signal");
  r.summary->stopped_by = app::kStopWallBudget;
  EXPECT_EQ(app::run_end(r), "max_wall");
  r.summary.reset();
  EXPECT_EQ(app::run_end(r), "numerical_failure");
}

TEST(RunSummary, JsonHoldsTheFieldsAndLeavesOutWhatIsNotFinite) {
  app::RunRecord r = finished(10, 0.5);
  r.max_steps = 10;
  r.summary->stopped_by = SIGUSR1;
  r.exit_code = 128 + SIGUSR1;
  r.summary->wall_s = std::numeric_limits<double>::quiet_NaN();
  const std::string j = app::run_summary_json(r);
  EXPECT_EQ(j.front(), '{') << j;
  EXPECT_TRUE(has(j, "\"format\" : \"mpmxdem run summary\"")) << j;
  EXPECT_TRUE(has(j, "\"ended\" : \"signal\"")) << j;
  EXPECT_TRUE(has(j, "\"signal\" : \"SIGUSR1\"")) << j;
  EXPECT_TRUE(has(j, "\"exit_code\" : " + std::to_string(128 + SIGUSR1))) << j;
  EXPECT_TRUE(has(j, "\"mpm_steps\" : 10")) << j;
  EXPECT_TRUE(has(j, "\"dem_steps\" : 400")) << j;
  EXPECT_TRUE(has(j, "\"out/checkpoint_0000000010.h5\"")) << j;
  EXPECT_FALSE(has(j, "wall_s")) << j;  // JSON has no NaN: left out
  EXPECT_FALSE(has(j, "nan")) << j;

  app::RunRecord failed;
  failed.exit_code = 3;
  failed.error = "mpm step 7 (t = 0.1 s): point id 3 has left the grid";
  const std::string f = app::run_summary_json(failed);
  EXPECT_TRUE(has(f, "\"ended\" : \"numerical_failure\"")) << f;
  EXPECT_TRUE(has(f, "\"error\" : \"mpm step 7 (t = 0.1 s): point id 3 has left the grid\"")) << f;
  EXPECT_FALSE(has(f, "mpm_steps")) << f;  // no loop summary to report
}

}  // namespace
