// app::StopSignals: a signal is recorded, not acted on, while the guard lives; the previous
// actions come back after it. (The whole path, a signal to a running `mpmxdem run` under mpiexec,
// is tests/app/stop_signal.sh.)
#include <gtest/gtest.h>

#include <csignal>

#include "app/run/stop_signals.hpp"

namespace {

// The action installed for `signal` now.
void (*current_action(int signal))(int) {
  struct sigaction now {};
  sigaction(signal, nullptr, &now);
  return now.sa_handler;
}

}  // namespace

TEST(StopSignals, TheFirstSignalIsRecordedAndTheProcessGoesOn) {
  const auto before = current_action(SIGUSR1);
  {
    const app::StopSignals guard;
    EXPECT_EQ(app::StopSignals::received(), 0);
    ASSERT_EQ(std::raise(SIGUSR1), 0);  // without the guard: the process would end here
    EXPECT_EQ(app::StopSignals::received(), SIGUSR1);
    ASSERT_EQ(std::raise(SIGTERM), 0);
    EXPECT_EQ(app::StopSignals::received(), SIGUSR1);  // the first one is kept
  }
  EXPECT_EQ(current_action(SIGUSR1), before);
  EXPECT_EQ(current_action(SIGTERM), SIG_DFL);
  const app::StopSignals again;  // a new guard starts with nothing received
  EXPECT_EQ(app::StopSignals::received(), 0);
  ASSERT_EQ(std::raise(SIGXCPU), 0);
  EXPECT_EQ(app::StopSignals::received(), SIGXCPU);
}

TEST(StopSignals, AnIgnoredSignalStaysIgnored) {
  std::signal(SIGUSR2, SIG_IGN);
  {
    const app::StopSignals guard;
    EXPECT_EQ(current_action(SIGUSR2), SIG_IGN);
    ASSERT_EQ(std::raise(SIGUSR2), 0);
    EXPECT_EQ(app::StopSignals::received(), 0);
    EXPECT_NE(current_action(SIGUSR1), SIG_IGN);  // the others are taken
  }
  EXPECT_EQ(current_action(SIGUSR2), SIG_IGN);
  std::signal(SIGUSR2, SIG_DFL);
}

TEST(StopSignals, Names) {
  EXPECT_EQ(app::signal_name(SIGUSR1), "SIGUSR1");
  EXPECT_EQ(app::signal_name(SIGTERM), "SIGTERM");
  EXPECT_EQ(app::signal_name(SIGUSR2), "SIGUSR2");
  EXPECT_EQ(app::signal_name(SIGHUP), "signal " + std::to_string(SIGHUP));
}
