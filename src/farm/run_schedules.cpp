// Schedules of a coupled run (see header).
#include "farm/run_schedules.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/errors.hpp"

namespace farm {

CheckpointSchedule::CheckpointSchedule(const CheckpointOptions& options,
                                       std::int64_t fault_abort_at, std::int64_t last_step,
                                       double now)
    : options_(options), fault_abort_at_(fault_abort_at), last_step_(last_step), last_wall_(now) {}

bool CheckpointSchedule::due(std::int64_t step, double now) const {
  return (options_.every_steps > 0 && step % options_.every_steps == 0) ||
         (options_.every_wall_s > 0.0 && now - last_wall_ >= options_.every_wall_s);
}

std::vector<std::string> CheckpointSchedule::expired(const std::vector<std::string>& all) const {
  const auto keep = static_cast<std::size_t>(options_.keep);
  if (all.size() <= keep) return {};
  return {all.begin(), all.end() - static_cast<std::ptrdiff_t>(keep)};
}

std::int64_t fault_abort_from_env(std::int64_t configured) {
  const char* env = std::getenv("MPMXDEM_FARM_FAULT");
  if (env == nullptr || *env == '\0') return configured;
  const std::string s(env);
  const std::string prefix = "abort_checkpoint:";
  if (s.rfind(prefix, 0) == 0) {
    try {
      const std::int64_t n = std::stoll(s.substr(prefix.size()));
      if (n >= 1) return n;
    } catch (const std::exception&) {
    }
  }
  throw common::InputError("farm config: MPMXDEM_FARM_FAULT (environment) = " + s +
                           ": must be abort_checkpoint:<n> with n >= 1");
}

double eta_s(std::int64_t step, double time, std::int64_t max_steps, double end_time,
             double per_step) {
  double left = max_steps > 0 ? static_cast<double>(max_steps - step) : 1e300;
  if (end_time > 0.0 && time > 0.0) {
    left = std::min(left, (end_time - time) / (time / static_cast<double>(step)));
  }
  return left * per_step;
}

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  // Beyond a million hours the count of hours would overflow nothing useful: years.
  if (s >= 3.6e9) return fmt::format("{:.3g} years", s / 3.15576e7);
  const auto t = static_cast<long long>(s);
  return std::to_string(t / 3600) + "h" + std::to_string((t / 60) % 60) + "m" +
         std::to_string(t % 60) + "s";
}

std::int64_t BalanceSchedule::checked(std::int64_t step, double now, double metis_s) {
  const std::int64_t steps = step - last_step_;
  const double step_s = steps > 0 ? (now - last_wall_) / static_cast<double>(steps) : 0.0;
  last_step_ = step;
  last_wall_ = now;
  std::int64_t wait = options_.check_every;
  if (metis_s > 0.0 && step_s > 0.0) {
    const double need = metis_s / (kMetisShare * step_s);
    if (need > static_cast<double>(wait)) {
      // Rounded up to a multiple of check_every: due() also asks step % check_every == 0.
      const auto k = static_cast<std::int64_t>(std::ceil(need / static_cast<double>(wait)));
      wait *= std::max<std::int64_t>(k, 1);
    }
  }
  next_ = step + wait;
  return wait;
}

}  // namespace farm
