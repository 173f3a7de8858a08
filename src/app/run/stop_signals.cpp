#include "app/run/stop_signals.hpp"

#include <atomic>
#include <cstring>

#include "common/errors.hpp"

namespace app {
namespace {

constexpr int kSignals[] = {SIGTERM, SIGINT, SIGUSR1, SIGUSR2, SIGXCPU};

// Lock-free: written from the handler, on whichever thread the signal lands (OpenMP, MPI).
std::atomic<int> g_received{0};
static_assert(std::atomic<int>::is_always_lock_free);
std::atomic<bool> g_installed{false};

extern "C" void on_stop_signal(int signal) {
  int none = 0;
  if (!g_received.compare_exchange_strong(none, signal) && signal == SIGINT) {
    // A second Ctrl-C: the user wants out now (signal and raise are async-signal-safe).
    std::signal(SIGINT, SIG_DFL);
    std::raise(SIGINT);
  }
}

}  // namespace

StopSignals::StopSignals() {
  MPMXDEM_CHECK(!g_installed.exchange(true), "StopSignals: one at a time");
  g_received.store(0);
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // interrupted reads and writes (HDF5, MPI) resume
  for (std::size_t k = 0; k < std::size(kSignals); ++k) {
    sigaction(kSignals[k], nullptr, &old_[k]);
    // A signal ignored when the process started stays ignored (`nohup`, SIGINT of a background
    // job of a script): whoever ignored it did not mean it to stop the run.
    if (old_[k].sa_handler != SIG_IGN) sigaction(kSignals[k], &action, nullptr);
  }
}

StopSignals::~StopSignals() {
  for (std::size_t k = 0; k < std::size(kSignals); ++k) sigaction(kSignals[k], &old_[k], nullptr);
  g_installed.store(false);
}

int StopSignals::received() { return g_received.load(); }

std::string signal_name(int signal) {
  switch (signal) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGUSR1:
      return "SIGUSR1";
    case SIGUSR2:
      return "SIGUSR2";
    case SIGXCPU:
      return "SIGXCPU";
    default:
      return "signal " + std::to_string(signal);
  }
}

}  // namespace app
