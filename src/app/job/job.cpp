// Job-file parsing (toml++) and schema validation: every problem is reported with file:line, the
// full key, the value read and the rule; unknown keys get a "did you mean".
#include "app/job/job.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/errors.hpp"

namespace app {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

namespace {

std::string join_path(const std::string& prefix, std::string_view key) {
  return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
}

std::string float_text(double x) {
  std::string t = fmt::format("{}", x);
  if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
  return t;
}

// The value as the user would write it (shortest round-trip floats, double-quoted strings).
std::string node_text_full(const toml::node& node) {
  if (node.is_table()) return "(a table)";
  if (const auto* a = node.as_array()) {
    std::vector<std::string> parts;
    for (const auto& el : *a) parts.push_back(node_text_full(el));
    return fmt::format("[{}]", fmt::join(parts, ", "));
  }
  if (const auto* i = node.as_integer()) return fmt::format("{}", i->get());
  if (const auto* f = node.as_floating_point()) return float_text(f->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* str = node.as_string()) return "\"" + str->get() + "\"";
  std::ostringstream os;
  node.visit([&os](const auto& n) { os << n; });
  return os.str();
}

std::string node_text(const toml::node& node) {
  std::string s = node_text_full(node);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

int node_line(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

std::string describe(const Key& key) {
  const std::string unit(canonical_unit(key.quantity));
  return unit.empty() ? key.doc : key.doc + " [" + unit + "]";
}

// A key as compared for suggestions: lower case, without '_', '-' and spaces ("End_Time" and
// "endtime" are the same word).
std::string normalized(std::string_view s) {
  std::string out;
  for (const char c : s) {
    if (c == '_' || c == '-' || c == ' ') continue;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

std::size_t common_prefix(std::string_view a, std::string_view b) {
  std::size_t n = 0;
  while (n < a.size() && n < b.size() && a[n] == b[n]) ++n;
  return n;
}

// The sibling key closest to `name`: edit distance of the normalized names; a name that holds the
// other whole (both at least 3 letters: "young" for "young_modulus") counts as distance 1; ties go
// to the longer common prefix. "" when nothing is close.
std::string suggestion(std::string_view name, const std::vector<const Key*>& candidates) {
  const std::string n = normalized(name);
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, n.size() / 3) + 1;
  std::size_t best_prefix = 0;
  for (const Key* k : candidates) {
    const std::string leaf = leaf_name(k->path);
    const std::string l = normalized(leaf);
    std::size_t d = edit_distance(n, l);
    if (std::min(n.size(), l.size()) >= 3 &&
        (l.find(n) != std::string::npos || n.find(l) != std::string::npos))
      d = std::min<std::size_t>(d, 1);
    const std::size_t prefix = common_prefix(n, l);
    if (d < best_d || (d == best_d && !best.empty() && prefix > best_prefix)) {
      best_d = d;
      best = leaf;
      best_prefix = prefix;
    }
  }
  return best;
}

// A key or name from the file, short enough to print (a 100 kB key is not echoed whole).
std::string clipped(std::string_view s) {
  return s.size() > 60 ? std::string(s.substr(0, 57)) + "..." : std::string(s);
}

}  // namespace

/// Walks the TOML tree against the schema and fills a Job; collects every error.
class Validator {
 public:
  Validator(Job& job, const Schema& schema) : job_(job), schema_(schema) {}

  void walk(const toml::table& table, const std::string& cprefix, const std::string& sprefix) {
    for (const auto& [k, node] : table) {
      const std::string cpath = join_path(cprefix, k.str());
      std::string spath = join_path(sprefix, k.str());
      const Key* key = schema_.find(spath);
      if (key == nullptr) key = schema_.find(spath + "[]");
      if (key == nullptr) {
        unknown(std::string(k.str()), static_cast<int>(k.source().begin.line), cpath, sprefix);
        continue;
      }
      if (key->type == Type::Table) {
        if (!node.is_table()) {
          invalid_.insert(cpath);
          error(node_line(node),
                fmt::format("{} = {}: must be a table [{}]", cpath, node_text(node), key->path));
          continue;
        }
        job_.sections_[cpath] = node_line(node);
        walk(*node.as_table(), cpath, key->path);
      } else if (key->type == Type::TableList) {
        const toml::array* arr = node.as_array();
        if (arr == nullptr || !arr->is_array_of_tables()) {
          error(node_line(node), fmt::format("{} = {}: must be an array of tables, written [[{}]]",
                                             cpath, node_text(node), cpath));
          job_.counts_[cpath] = 0;  // present, though wrong: no second "missing" error
          continue;
        }
        job_.counts_[cpath] = arr->size();
        for (std::size_t i = 0; i < arr->size(); ++i) {
          const std::string elem = fmt::format("{}[{}]", cpath, i);
          job_.sections_[elem] = node_line(*arr->get(i));
          walk(*arr->get(i)->as_table(), elem, key->path);
        }
      } else {
        scalar(*key, node, cpath);
      }
    }
    fill_absent(cprefix, sprefix, true);
  }

  void error(int line, const std::string& msg) {
    errors_.push_back(line > 0 ? fmt::format("{}:{}: {}", job_.file_, line, msg)
                               : fmt::format("{}: {}", job_.file_, msg));
  }
  [[nodiscard]] const std::vector<std::string>& errors() const { return errors_; }

 private:
  // Required keys that are absent are errors; absent keys with a default are filled. An absent
  // optional section gets its defaults but is not checked for required keys.
  void fill_absent(const std::string& cprefix, const std::string& sprefix, bool present) {
    for (const Key* child : schema_.children(sprefix)) {
      const std::string leaf = leaf_name(child->path);
      const std::string cpath = join_path(cprefix, leaf);
      if (child->type == Type::TableList) {
        if (present && child->required && job_.counts_.count(cpath) == 0) {
          error(section_line(cprefix),
                fmt::format("{}: at least one [[{}]] is required ({})", cpath, cpath, child->doc));
        }
        continue;
      }
      if (child->type == Type::Table) {
        if (job_.sections_.count(cpath) != 0 || invalid_.count(cpath) != 0) continue;
        if (present && child->required) {
          error(section_line(cprefix),
                fmt::format("[{}] is missing: required section ({})", cpath, child->doc));
        }
        // An absent section with required keys is physics or a feature switched off: no
        // defaults. An absent section of knobs only (output, numerics) takes its defaults.
        if (!has_required_descendant(child->path)) fill_absent(cpath, child->path, false);
        continue;
      }
      if (job_.entries_.count(cpath) != 0 || invalid_.count(cpath) != 0) continue;
      if (child->fallback) {
        job_.entries_[cpath] = Entry{*child->fallback, 0, true, child, ""};
      } else if (present && child->required) {
        error(section_line(cprefix),
              fmt::format("{} is missing: required ({})", cpath, describe(*child)));
      }
    }
  }

  bool has_required_descendant(const std::string& spath) const {
    for (const Key* k : schema_.children(spath)) {
      if (k->required || ((k->type == Type::Table || k->type == Type::TableList) &&
                          has_required_descendant(k->path)))
        return true;
    }
    return false;
  }

  int section_line(const std::string& cpath) const {
    auto it = job_.sections_.find(cpath);
    return it == job_.sections_.end() ? 0 : it->second;
  }

  void unknown(const std::string& name, int line, const std::string& cpath,
               const std::string& sprefix) {
    const auto siblings = schema_.children(sprefix);
    std::string msg = fmt::format("{}: unknown key", clipped(cpath));
    const std::string best = suggestion(name, siblings);
    if (!best.empty()) msg += fmt::format("; did you mean '{}'?", best);
    std::vector<std::string> names;
    for (const Key* k : siblings) names.push_back(leaf_name(k->path));
    msg += fmt::format(" (keys of {}: {})", sprefix.empty() ? "the top level" : "[" + sprefix + "]",
                       fmt::join(names, ", "));
    error(line, msg);
  }

  // Reads one number (int, float, or "<number> <unit>" string) into the canonical unit.
  std::optional<double> read_number(const Key& key, const toml::node& node,
                                    std::string& why) const {
    if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
    if (const auto* f = node.as_floating_point()) {
      if (!std::isfinite(f->get())) {
        why = "must be finite";
        return std::nullopt;
      }
      return f->get();
    }
    if (const auto* s = node.as_string()) return parse_quantity(s->get(), key.quantity, why);
    why = key.quantity == Quantity::Dimensionless
              ? "must be a number"
              : fmt::format("must be a number (in {}) or a string with a unit ({})",
                            canonical_unit(key.quantity), accepted_units(key.quantity));
    return std::nullopt;
  }

  bool in_range(const Key& key, double v) const {
    if (key.min && (key.min_open ? v <= *key.min : v < *key.min)) return false;
    if (key.max && (key.max_open ? v >= *key.max : v > *key.max)) return false;
    return true;
  }

  // The rule a string outside key.choices breaks, with a "did you mean" for a near choice.
  static std::string choice_rule(const Key& key, const std::string& s) {
    std::string rule = fmt::format("must be one of {}", fmt::join(key.choices, ", "));
    std::size_t best_d = 3;
    std::string best;
    for (const auto& c : key.choices) {
      const std::size_t d = edit_distance(s, c);
      if (d < best_d) {
        best_d = d;
        best = c;
      }
    }
    if (!best.empty()) rule += fmt::format("; did you mean '{}'?", best);
    return rule;
  }

  // Reads a list key (Type::FloatList or Type::IntList) into value; returns the rule the list
  // breaks, or "" when it is valid (value then set).
  std::string read_list(const Key& key, const toml::node& node, Value& value) const {
    const auto* arr = node.as_array();
    if (arr == nullptr) return fmt::format("must be {}", type_name(key));
    if (arr->size() < key.min_len || arr->size() > key.max_len) {
      return key.min_len == key.max_len
                 ? fmt::format("must have {} entries, not {}", key.min_len, arr->size())
                 : fmt::format("must have {} to {} entries, not {}", key.min_len, key.max_len,
                               arr->size());
    }
    std::vector<double> fv;
    std::vector<std::int64_t> iv;
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::node& el = *arr->get(i);
      if (key.type == Type::IntList) {
        const auto* n = el.as_integer();
        if (n == nullptr) return fmt::format("entry {} must be an integer", i + 1);
        if (!in_range(key, static_cast<double>(n->get())))
          return fmt::format("entry {}: {}", i + 1, range_rule(key));
        iv.push_back(n->get());
      } else {
        std::string why;
        const auto v = read_number(key, el, why);
        if (!v) return fmt::format("entry {} {}", i + 1, why);
        if (!in_range(key, *v)) return fmt::format("entry {}: {}", i + 1, range_rule(key));
        fv.push_back(*v);
      }
    }
    if (key.type == Type::IntList) {
      value = std::move(iv);
    } else {
      value = std::move(fv);
    }
    return {};
  }

  void scalar(const Key& key, const toml::node& node, const std::string& cpath) {
    const int line = node_line(node);
    const std::string raw = node_text(node);
    auto fail = [&](const std::string& rule) {
      invalid_.insert(cpath);  // reported once: not "missing" as well
      error(line, fmt::format("{} = {}: {} [{}]", cpath, raw, rule, describe(key)));
    };
    Value value;
    switch (key.type) {
      case Type::Float: {
        std::string why;
        const auto v = read_number(key, node, why);
        if (!v) return fail(why);
        if (!in_range(key, *v)) return fail(range_rule(key));
        value = *v;
        break;
      }
      case Type::Int: {
        if (const auto* arr = node.as_array(); arr != nullptr && key.per_axis) {
          // One integer per axis.
          if (arr->size() != 3) {
            return fail(fmt::format("must be an integer or a list of 3 integers, not {} entries",
                                    arr->size()));
          }
          std::vector<std::int64_t> iv;
          for (std::size_t k = 0; k < arr->size(); ++k) {
            const auto* n = arr->get(k)->as_integer();
            if (n == nullptr) return fail(fmt::format("entry {} must be an integer", k + 1));
            if (!in_range(key, static_cast<double>(n->get())))
              return fail(fmt::format("entry {}: {}", k + 1, range_rule(key)));
            iv.push_back(n->get());
          }
          value = std::move(iv);
          break;
        }
        const auto* i = node.as_integer();
        if (i == nullptr) return fail("must be an integer");
        if (!in_range(key, static_cast<double>(i->get()))) return fail(range_rule(key));
        value = i->get();
        break;
      }
      case Type::Bool: {
        const auto* b = node.as_boolean();
        if (b == nullptr) return fail("must be true or false");
        value = b->get();
        break;
      }
      case Type::String: {
        const auto* s = node.as_string();
        if (s == nullptr) return fail("must be a string");
        if (!key.choices.empty() &&
            std::find(key.choices.begin(), key.choices.end(), s->get()) == key.choices.end()) {
          return fail(choice_rule(key, s->get()));
        }
        value = s->get();
        break;
      }
      case Type::FloatList:
      case Type::IntList: {
        if (std::string rule = read_list(key, node, value); !rule.empty()) return fail(rule);
        break;
      }
      case Type::Table:
      case Type::TableList:
        return;
    }
    job_.entries_[cpath] = Entry{std::move(value), line, false, &key, raw};
  }

  Job& job_;
  const Schema& schema_;
  std::vector<std::string> errors_;
  std::set<std::string> invalid_;  ///< keys present with an invalid value
};

Job Job::parse(std::string_view text, std::string file, const Schema& schema, bool rules) {
  Job job;
  job.file_ = std::move(file);
  job.text_ = std::string(text);
  job.schema_ = &schema;
  toml::table root;
  try {
    root = toml::parse(text, job.file_);
  } catch (const toml::parse_error& e) {
    throw common::InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", job.file_,
                                         e.source().begin.line, e.source().begin.column,
                                         e.description()));
  }
  if (root.empty()) {
    throw common::InputError(
        fmt::format("{}: the job file is empty: it needs at least the required sections "
                    "(see docs/reference/jobs.md or `mpmxdem schema`)",
                    job.file_));
  }
  Validator v(job, schema);
  v.walk(root, "", "");
  if (!v.errors().empty()) throw common::InputError(fmt::format("{}", fmt::join(v.errors(), "\n")));
  if (rules) check_job_rules(job);  // cross-key rules only make sense once every key is valid
  return job;
}

Job Job::load(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw common::InputError(fmt::format("{}: cannot open the job file: no such file", path));
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw common::InputError(fmt::format("{}: cannot open the job file: it is a directory", path));
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw common::InputError(fmt::format(
        "{}: cannot open the job file: not a regular file (a device or a pipe?)", path));
  }
  constexpr std::uintmax_t kMaxJobBytes = 16u << 20;  // job files are a few kB
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxJobBytes) {
    throw common::InputError(fmt::format(
        "{}: the job file has {} bytes, more than the {} a job file may have: is it a job file?",
        path, size, kMaxJobBytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw common::InputError(fmt::format("{}: cannot open the job file: permission denied?", path));
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

bool Job::has_section(const std::string& path) const { return sections_.count(path) != 0; }

std::size_t Job::count(const std::string& path) const {
  auto it = counts_.find(path);
  return it == counts_.end() ? 0 : it->second;
}

const Entry& Job::entry(const std::string& path) const {
  auto it = entries_.find(path);
  if (it == entries_.end()) throw common::InternalError("job key '" + path + "' was not resolved");
  return it->second;
}

namespace {
template <class T>
const T& get_as(const Entry& e, const std::string& path) {
  const T* v = std::get_if<T>(&e.value);
  if (v == nullptr) throw common::InternalError("job key '" + path + "' read with the wrong type");
  return *v;
}
}  // namespace

double Job::number(const std::string& path) const { return get_as<double>(entry(path), path); }
std::int64_t Job::integer(const std::string& path) const {
  return get_as<std::int64_t>(entry(path), path);
}
bool Job::flag(const std::string& path) const { return get_as<bool>(entry(path), path); }
const std::string& Job::text(const std::string& path) const {
  return get_as<std::string>(entry(path), path);
}
const std::vector<double>& Job::numbers(const std::string& path) const {
  return get_as<std::vector<double>>(entry(path), path);
}
const std::vector<std::int64_t>& Job::integers(const std::string& path) const {
  return get_as<std::vector<std::int64_t>>(entry(path), path);
}
std::array<std::int64_t, 3> Job::per_axis(const std::string& path) const {
  const Entry& e = entry(path);
  if (const auto* list = std::get_if<std::vector<std::int64_t>>(&e.value)) {
    return {(*list)[0], (*list)[1], (*list)[2]};
  }
  const std::int64_t n = get_as<std::int64_t>(e, path);
  return {n, n, n};
}

std::string Job::message(const std::string& path, const std::string& rule) const {
  auto it = entries_.find(path);
  if (it == entries_.end()) return missing_message(path, rule);
  const Entry& e = it->second;
  const std::string where = e.line > 0 ? fmt::format("{}:{}", file_, e.line) : file_;
  const std::string raw = e.defaulted ? "(default)" : e.raw;
  return fmt::format("{}: {} = {}: {}", where, path, raw, rule);
}

std::string Job::missing_message(const std::string& path, const std::string& rule) const {
  const std::string parent = parent_path(path);
  auto it = sections_.find(parent);
  const int line = it == sections_.end() ? 0 : it->second;
  const std::string where = line > 0 ? fmt::format("{}:{}", file_, line) : file_;
  return fmt::format("{}: {} is missing: {}", where, path, rule);
}

std::string Job::section_message(const std::string& path, const std::string& rule) const {
  auto it = sections_.find(path);
  const int line = it == sections_.end() ? 0 : it->second;
  const std::string where = line > 0 ? fmt::format("{}:{}", file_, line) : file_;
  return fmt::format("{}: [{}]: {}", where, path, rule);
}

std::string Job::directory() const { return std::filesystem::path(file_).parent_path().string(); }

namespace {
std::string toml_value(const Value& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::string>) {
          std::ostringstream os;
          os << toml::value<std::string>(x);
          return os.str();
        } else if constexpr (std::is_same_v<T, bool>) {
          return x ? "true" : "false";
        } else if constexpr (std::is_same_v<T, double>) {
          std::string s = fmt::format("{}", x);
          if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
          return s;
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          std::vector<std::string> parts;
          for (double d : x) parts.push_back(toml_value(Value{d}));
          return fmt::format("[{}]", fmt::join(parts, ", "));
        } else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) {
          return fmt::format("[{}]", fmt::join(x, ", "));
        } else {
          return fmt::format("{}", x);
        }
      },
      v);
}

}  // namespace

std::string value_text(const Value& value) { return toml_value(value); }

namespace {
std::string entry_line(const std::string& name, const Entry& e) {
  std::string line = fmt::format("{} = {}", name, toml_value(e.value));
  const std::string unit = e.key != nullptr ? std::string(canonical_unit(e.key->quantity)) : "";
  if (!unit.empty() || e.defaulted) {
    line += "  #";
    if (!unit.empty()) line += " " + unit;
    if (e.defaulted) line += " (default)";
  }
  return line + "\n";
}
}  // namespace

std::string Job::resolved_toml() const {
  std::ostringstream out;
  out << "# Resolved job: every key with its value in the canonical unit, defaults filled.\n"
      << "# Source: " << file_ << "\n";
  std::vector<std::pair<std::string, std::string>> arrays;  // element path, header
  for (const auto& [path, e] : entries_) {
    if (path.find('[') != std::string::npos) continue;
    out << entry_line(path, e);
  }
  for (const auto& [path, n] : counts_) {
    for (std::size_t i = 0; i < n; ++i) {
      out << "\n[[" << path << "]]\n";
      const std::string prefix = fmt::format("{}[{}].", path, i);
      for (const auto& [p, e] : entries_) {
        if (p.starts_with(prefix) && p.find('[', prefix.size()) == std::string::npos) {
          out << entry_line(p.substr(prefix.size()), e);
        }
      }
    }
  }
  return out.str();
}

}  // namespace app
