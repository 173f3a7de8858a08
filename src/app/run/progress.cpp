// Progress reporting: see progress.hpp.
#include "app/run/progress.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace app {

Progress::Progress(std::string what, double total, double interval_seconds)
    : what_(std::move(what)),
      total_(total),
      interval_(interval_seconds),
      start_(Clock::now()),
      last_(start_) {}

std::string Progress::clock(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--:--";
  if (seconds >= 3.6e9) return fmt::format("{:.3g} years", seconds / 3.15576e7);
  const auto s = static_cast<long long>(seconds + 0.5);
  return fmt::format("{:02d}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

void Progress::update(double done, long long steps, const std::string& detail, bool force) {
  const auto now = Clock::now();
  const bool first = start_steps_ < 0;
  if (first) start_steps_ = steps;
  if (!force && !first && std::chrono::duration<double>(now - last_).count() < interval_) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = total_ > 0 ? std::clamp(done / total_, 0.0, 1.0) : 1.0;
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  const double rate = elapsed > 0 ? static_cast<double>(steps - start_steps_) / elapsed : 0.0;
  spdlog::info("{} {:.1f} % ({:.4g} of {:.4g}), {:.0f} steps/s, elapsed {}, ETA {}{}{}", what_,
               100.0 * fraction, done, total_, rate, clock(elapsed), clock(eta),
               detail.empty() ? "" : "; ", detail);
}

}  // namespace app
