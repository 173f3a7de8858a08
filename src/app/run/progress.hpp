// Progress lines with an ETA for long runs, at most one every `interval` seconds of wall time:
// "triaxial 12.3 % (eps_a 0.0369 of 0.3), 410 steps/s, elapsed 00:01:02, ETA 00:07:21; q/p 1.93".
#pragma once

#include <chrono>
#include <string>

namespace app {

class Progress {
 public:
  /// `what` names the phase; `total` is the amount of work (any unit, e.g. a strain).
  Progress(std::string what, double total, double interval_seconds = 10.0);
  /// Reports progress `done` (same unit as total) after `steps` steps in all; logs (spdlog info)
  /// on the first call, when the interval has passed, or when `force`. `detail` is appended.
  void update(double done, long long steps, const std::string& detail, bool force = false);
  /// Formats seconds as hh:mm:ss.
  [[nodiscard]] static std::string clock(double seconds);

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_;
  double total_;
  double interval_;
  Clock::time_point start_;
  Clock::time_point last_;
  long long start_steps_ = -1;
};

}  // namespace app
