// Unit tests of farm/run_schedules.hpp: when a coupled run writes outputs and checkpoints, which
// checkpoints it keeps, when it balances.
#include <gtest/gtest.h>

#include <cstdlib>

#include "common/errors.hpp"
#include "farm/run_schedules.hpp"

namespace {

TEST(RunSchedules, OutputEveryNAndAtTheEnd) {
  const farm::OutputSchedule o(10);
  EXPECT_TRUE(o.due(20));
  EXPECT_FALSE(o.due(25));
  EXPECT_TRUE(o.due_at_end(25, 3));
  EXPECT_FALSE(o.due_at_end(30, 4));
  EXPECT_TRUE(o.due_at_end(30, 0));
}

TEST(RunSchedules, CheckpointsByStepsWallTimeAndAtTheEnd) {
  farm::CheckpointOptions opt;
  opt.every_steps = 5;
  opt.every_wall_s = 60.0;
  opt.keep = 2;
  farm::CheckpointSchedule c(opt, 2, -1, 1000.0);
  EXPECT_TRUE(c.due(10, 1000.0));
  EXPECT_FALSE(c.due(11, 1059.0));
  EXPECT_TRUE(c.due(11, 1060.0));
  c.restart_clock(1060.0);
  EXPECT_FALSE(c.due(12, 1100.0));
  EXPECT_FALSE(c.begin_write());  // write 1
  c.written(12);
  EXPECT_FALSE(c.due_at_end(12));
  EXPECT_TRUE(c.due_at_end(13));
  EXPECT_TRUE(c.begin_write());  // write 2: the injected fault
  EXPECT_EQ(c.expired({"a", "b", "c", "d"}), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(c.expired({"a", "b"}).empty());
  opt.at_end = false;
  EXPECT_FALSE(farm::CheckpointSchedule(opt, 0, -1, 0.0).due_at_end(13));
}

TEST(RunSchedules, BalanceOnlyWithRanksToBalance) {
  farm::BalanceOptions b;
  EXPECT_EQ(b.threshold, 1.2);  // the job file's default (docs/design/farm.md, "Balancing")
  b.check_every = 4;
  EXPECT_TRUE(farm::BalanceSchedule(b, 2).due(8));
  EXPECT_FALSE(farm::BalanceSchedule(b, 2).due(6));
  EXPECT_FALSE(farm::BalanceSchedule(b, 1).due(8));
  b.enabled = false;
  EXPECT_FALSE(farm::BalanceSchedule(b, 2).due(8));
}

TEST(RunSchedules, ProgressAtTheFirstStepThenAtMostEverySoManySeconds) {
  farm::ProgressSchedule p(10.0, 0.0);
  EXPECT_TRUE(p.due(0.5));  // the first step: an ETA at once
  EXPECT_FALSE(p.due(9.0));
  EXPECT_TRUE(p.due(10.5));
  EXPECT_FALSE(p.due(19.0));
  EXPECT_TRUE(p.due(20.5));
}

TEST(RunSchedules, FaultInjectionFromTheEnvironment) {
  ::unsetenv("MPMXDEM_FARM_FAULT");
  EXPECT_EQ(farm::fault_abort_from_env(3), 3);
  ::setenv("MPMXDEM_FARM_FAULT", "abort_checkpoint:2", 1);
  EXPECT_EQ(farm::fault_abort_from_env(0), 2);
  ::setenv("MPMXDEM_FARM_FAULT", "abort_checkpoint:0", 1);
  EXPECT_THROW(farm::fault_abort_from_env(0), common::InputError);
  ::setenv("MPMXDEM_FARM_FAULT", "crash", 1);
  EXPECT_THROW(farm::fault_abort_from_env(0), common::InputError);
  ::unsetenv("MPMXDEM_FARM_FAULT");
}

TEST(RunSchedules, EtaAndDurations) {
  EXPECT_DOUBLE_EQ(farm::eta_s(10, 1.0, 110, 0.0, 2.0), 200.0);
  // end_time first: 1 s of 10 done in 10 steps -> 90 steps left.
  EXPECT_DOUBLE_EQ(farm::eta_s(10, 1.0, 1000, 10.0, 1.0), 90.0);
  EXPECT_EQ(farm::format_duration(3723.0), "1h2m3s");
  EXPECT_EQ(farm::format_duration(-1.0), "?");
  // Beyond a million hours, years (a count of hours would overflow the integer it is made of).
  EXPECT_EQ(farm::format_duration(3.6e9 - 1.0), "999999h59m59s");
  EXPECT_EQ(farm::format_duration(1e300), "3.17e+292 years");
}

// Finding 3 of docs/validation/scaling.md: a check whose METIS proposal took 0.25 s with steps of 15 ms
// (10^4 RVEs on 1024 ranks) makes the next one wait 0.25 / (0.01 * 0.015) = 1667 steps, rounded
// up to a multiple of check_every (1680): METIS then costs at most 1 % of the run. A check
// without a proposal (imbalance below the threshold) or a cheap one keeps check_every.
TEST(RunSchedules, BalanceChecksAreSpacedByTheMetisTime) {
  farm::BalanceOptions b;
  b.check_every = 20;
  farm::BalanceSchedule s(b, 1024);
  s.start(0, 100.0);
  EXPECT_TRUE(s.due(20));
  EXPECT_EQ(s.checked(20, 100.0 + 20 * 0.015, 0.25), 1680);
  EXPECT_FALSE(s.due(40));
  EXPECT_FALSE(s.due(1680));
  EXPECT_TRUE(s.due(1700));
  // The next check made no proposal: back to every 20 steps.
  EXPECT_EQ(s.checked(1700, 100.3 + 1680 * 0.015, 0.0), 20);
  EXPECT_TRUE(s.due(1720));
  // A proposal cheaper than 1 % of check_every steps changes nothing.
  EXPECT_EQ(s.checked(1720, 100.3 + 1700 * 0.015, 0.001), 20);
}

}  // namespace
