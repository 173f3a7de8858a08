// run_summary.json (run_summary.hpp): built as a toml++ table and printed by its JSON formatter,
// so that no JSON library is needed.
#include "app/run/run_summary.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <sstream>

#include "app/commands/version.hpp"
#include "app/run/output_dir.hpp"
#include "app/run/stop_signals.hpp"
#include "app/run/wall_budget.hpp"

namespace app {

namespace {

// JSON has no NaN or infinity: a quantity that is not finite is left out.
void put(toml::table& t, std::string_view key, double v) {
  if (std::isfinite(v)) t.insert_or_assign(key, v);
}

}  // namespace

std::string run_end(const RunRecord& r) {
  if (!r.summary) return "numerical_failure";
  const farm::RunSummary& s = *r.summary;
  if (s.stopped_by == kStopWallBudget) return "max_wall";
  if (s.stopped_by != 0) return "signal";
  if (r.max_steps > 0 && s.steps >= r.max_steps && s.time < r.end_time) return "max_steps";
  return "end_time";
}

std::string run_summary_json(const RunRecord& r) {
  toml::table t;
  t.insert_or_assign("format", "mpmxdem run summary");
  t.insert_or_assign("format_version", 1);
  t.insert_or_assign("software", "mpmxdem");
  t.insert_or_assign("software_version", kVersion);
  t.insert_or_assign("job", r.job);
  t.insert_or_assign("restart", r.restart);
  t.insert_or_assign("ranks", r.ranks);
  t.insert_or_assign("threads_per_rank", r.threads);
  put(t, "end_time_s", r.end_time);
  t.insert_or_assign("ended", run_end(r));
  t.insert_or_assign("exit_code", r.exit_code);
  t.insert_or_assign("error", r.error);
  if (r.summary) {
    const farm::RunSummary& s = *r.summary;
    t.insert_or_assign("signal", s.stopped_by > 0 ? signal_name(s.stopped_by) : std::string());
    t.insert_or_assign("mpm_steps", s.steps);
    put(t, "time_s", s.time);
    put(t, "wall_s", s.wall_s);
    put(t, "rve_time_critical_rank_s", s.times.critical_busy);
    put(t, "balance", run_balance(s));
    t.insert_or_assign("migrations", s.migrations);
    t.insert_or_assign("rves_moved", s.rves_moved);
    t.insert_or_assign("dem_steps", s.dem_steps);
    t.insert_or_assign("rve_steps", s.rve_steps);
    t.insert_or_assign("spared_rve_steps", s.spared_steps);
    toml::array checkpoints;
    for (const auto& c : s.checkpoints) checkpoints.push_back(c);
    t.insert_or_assign("checkpoints", std::move(checkpoints));
  }
  std::ostringstream os;
  os << toml::json_formatter{t} << '\n';
  return os.str();
}

void write_run_summary(const std::filesystem::path& dir, const RunRecord& r) {
  write_file_atomic(dir / kRunSummaryFile, run_summary_json(r));
}

}  // namespace app
