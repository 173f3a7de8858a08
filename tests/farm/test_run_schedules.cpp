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
  EXPECT_EQ(b.threshold, 1.2);  // the job file's default (docs/farm.md, "Balancing")
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
}

}  // namespace
