// Stopping a coupled run on a signal with a checkpoint (docs/reference/errors.md "Stopping a run"): the
// batch system's warning before a time limit (Slurm `--signal=USR1@300`, SGE's SIGUSR2), its
// SIGTERM at the limit, Ctrl-C. The handler only records the signal; rank 0 reads it after each
// MPM step, writes a checkpoint and ends the run there, and every rank exits 128 + the signal.
#pragma once

#include <csignal>
#include <string>

namespace app {

/// While alive: SIGTERM, SIGINT, SIGUSR1, SIGUSR2 and SIGXCPU are recorded (the first one;
/// a second SIGINT ends the process at once, as without the handler), not acted on; one that was
/// ignored (SIG_IGN: `nohup`, a script's background job) stays ignored. Restores the previous
/// actions when destroyed. One at a time per process.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// The first signal received since construction, 0 if none (async-signal-safe to update).
  [[nodiscard]] static int received();

 private:
  struct sigaction old_[5];
};

/// "SIGUSR1" for SIGUSR1, and so on for the signals above; "signal N" otherwise.
[[nodiscard]] std::string signal_name(int signal);

}  // namespace app
