// Restart compatibility of a job and a checkpoint: see restart_check.hpp.
#include "app/run/restart_check.hpp"

#include <fmt/format.h>

#include <set>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"

namespace app {

namespace fs = std::filesystem;

bool restart_may_change(const std::string& key) {
  return key == "title" || key == "mpm.end_time" || key.starts_with("output.") ||
         key.starts_with("farm.");
}

std::vector<std::string> changed_physics(const Job& before, const Job& now) {
  std::set<std::string> keys;
  for (const auto& [k, e] : before.entries()) keys.insert(k);
  for (const auto& [k, e] : now.entries()) keys.insert(k);
  std::vector<std::string> out;
  for (const std::string& k : keys) {
    if (restart_may_change(k)) continue;
    const auto a = before.entries().find(k);
    const auto b = now.entries().find(k);
    const bool has_a = a != before.entries().end();
    const bool has_b = b != now.entries().end();
    if (has_a && has_b && a->second.value == b->second.value) continue;
    out.push_back(fmt::format("{} = {} -> {}", k, has_a ? value_text(a->second.value) : "(absent)",
                              has_b ? value_text(b->second.value) : "(absent)"));
  }
  return out;
}

namespace {

// The stored job, parsed against the schema without its cross-key rules (they look for files
// relative to the job's directory, which the stored text no longer has).
Job stored_job(const std::string& text, const std::string& name) {
  try {
    return Job::parse(text, name, job_schema(), false);
  } catch (const common::InputError& e) {
    throw common::InputError(fmt::format(
        "{}: the job stored in it does not validate against this version's schema, so what it "
        "continues cannot be checked:\n{}",
        name, e.what()));
  }
}

std::string list(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += "\n  " + l;
  return s;
}

}  // namespace

void check_restart(const Job& job, const std::string& checkpoint_path,
                   const std::string& checkpoint_job, const fs::path& out) {
  const Job before = stored_job(checkpoint_job, checkpoint_path + ":/job");
  if (const auto changed = changed_physics(before, job); !changed.empty()) {
    throw common::InputError(fmt::format(
        "{}: cannot restart from {}: the job differs from the one the checkpoint was written "
        "with in {} key(s) a restart may not change (checkpoint -> job):{}\n(a restart may change "
        "only title, mpm.end_time, output.* and farm.*; start a new run for anything else)",
        job.file(), checkpoint_path, changed.size(), list(changed)));
  }
  std::error_code ec;
  const fs::path job_toml = out / "job.toml";
  if (fs::exists(job_toml, ec)) {
    const Job there = stored_job(common::read_file_bytes(job_toml), job_toml.string());
    if (const auto changed = changed_physics(before, there); !changed.empty()) {
      throw common::InputError(fmt::format(
          "output directory '{}' holds the results of another run: its job.toml differs from the "
          "job of checkpoint {} (checkpoint -> directory):{}\nrestart into that run's own "
          "directory, or into a new one with --out",
          out.string(), checkpoint_path, list(changed)));
    }
  } else if (fs::exists(out / "results.h5", ec)) {
    throw common::InputError(fmt::format(
        "output directory '{}' holds results.h5 but no job.toml: it cannot be the directory of "
        "the run of checkpoint {}; restart into that run's own directory, or into a new one "
        "with --out",
        out.string(), checkpoint_path));
  }
}

}  // namespace app
