// A validated job: every value of the job file resolved against the schema (defaults filled), with
// the line it came from, so that later checks can still name file:line, key, value and rule.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "app/job/schema.hpp"

namespace app {

struct Entry {
  Value value;
  int line = 0;  ///< 0: not from the file (a default)
  bool defaulted = false;
  const Key* key = nullptr;
  std::string raw;  ///< the value as written in the file
};

class Job {
 public:
  /// Parses and validates job text. `file` is the name used in messages. Throws common::InputError
  /// listing every problem found, one per line ("file:line: key = value: rule").
  /// `rules` = false skips the cross-key rules (check_job_rules): for a job stored in a checkpoint.
  static Job parse(std::string_view text, std::string file, const Schema& schema = job_schema(),
                   bool rules = true);
  /// Reads the file, then parse(). A missing or unreadable file is an InputError.
  static Job load(const std::string& path);

  [[nodiscard]] bool has(const std::string& path) const { return entries_.count(path) != 0; }
  /// True when the section (table) was written in the file.
  [[nodiscard]] bool has_section(const std::string& path) const;
  /// Number of elements of a table array ("mpm.body").
  [[nodiscard]] std::size_t count(const std::string& path) const;

  [[nodiscard]] double number(const std::string& path) const;
  [[nodiscard]] std::int64_t integer(const std::string& path) const;
  [[nodiscard]] bool flag(const std::string& path) const;
  [[nodiscard]] const std::string& text(const std::string& path) const;
  [[nodiscard]] const std::vector<double>& numbers(const std::string& path) const;
  [[nodiscard]] const std::vector<std::int64_t>& integers(const std::string& path) const;
  /// A per-axis integer key (Key::or_per_axis): n as {n, n, n}, or the list of 3 as written.
  [[nodiscard]] std::array<std::int64_t, 3> per_axis(const std::string& path) const;

  /// An InputError about key `path` ("file:line: path = value: rule"); for cross-key checks.
  [[nodiscard]] std::string message(const std::string& path, const std::string& rule) const;
  /// A message for a key that should be present but is not.
  [[nodiscard]] std::string missing_message(const std::string& path, const std::string& rule) const;
  /// "file:line: [path]: rule" for a table of the job (its header's line).
  [[nodiscard]] std::string section_message(const std::string& path, const std::string& rule) const;

  /// The resolved job as TOML, defaults included and marked, canonical units.
  [[nodiscard]] std::string resolved_toml() const;

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] const std::string& source_text() const { return text_; }
  /// Directory of the job file ("" for the current one): relative paths in the job are relative to
  /// it.
  [[nodiscard]] std::string directory() const;
  [[nodiscard]] const std::map<std::string, Entry>& entries() const { return entries_; }

 private:
  friend class Validator;
  const Entry& entry(const std::string& path) const;
  std::string file_;
  std::string text_;
  std::map<std::string, Entry> entries_;
  std::map<std::string, int> sections_;  ///< table path -> line of its header (0: implicit)
  std::map<std::string, std::size_t> counts_;
  const Schema* schema_ = nullptr;
};

/// Cross-key rules (job_rules.cpp): throws an InputError listing every broken rule.
void check_job_rules(const Job& job);

/// A value as TOML writes it (canonical unit): 1.0, "text", [1, 2].
[[nodiscard]] std::string value_text(const Value& value);

/// Edit distance for "did you mean" suggestions.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace app
