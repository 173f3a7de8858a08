// Schema helpers, range rules and the Markdown reference generated from the schema.
#include "app/job/schema.hpp"

#include <fmt/format.h>

#include <sstream>

namespace app {

std::string parent_path(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? std::string() : path.substr(0, dot);
}

std::string leaf_name(const std::string& path) {
  const auto dot = path.rfind('.');
  std::string leaf = dot == std::string::npos ? path : path.substr(dot + 1);
  if (leaf.size() > 2 && leaf.ends_with("[]")) leaf.resize(leaf.size() - 2);
  return leaf;
}

const Key* Schema::find(const std::string& path) const {
  for (const auto& k : keys) {
    if (k.path == path) return &k;
  }
  return nullptr;
}

std::vector<const Key*> Schema::children(const std::string& parent) const {
  std::vector<const Key*> out;
  for (const auto& k : keys) {
    std::string p = parent_path(k.path);
    if (p == parent) out.push_back(&k);
  }
  return out;
}

std::string Schema::section_doc(const std::string& path) const {
  const Key* k = find(path);
  return k != nullptr ? k->doc : std::string();
}

namespace {
std::string num(double v) { return fmt::format("{:g}", v); }
}  // namespace

std::string range_rule(const Key& key) {
  const std::string unit(canonical_unit(key.quantity));
  const std::string u = unit.empty() ? "" : " " + unit;
  if (key.min && key.max) {
    return fmt::format("must be in {}{}, {}{}{}", key.min_open ? "(" : "[", num(*key.min),
                       num(*key.max), key.max_open ? ")" : "]", u);
  }
  if (key.min) return fmt::format("must be {} {}{}", key.min_open ? ">" : ">=", num(*key.min), u);
  if (key.max) return fmt::format("must be {} {}{}", key.max_open ? "<" : "<=", num(*key.max), u);
  return {};
}

std::string type_name(const Key& key) {
  auto count = [&key](const char* what) {
    if (key.min_len == key.max_len) return fmt::format("a list of {} {}", key.min_len, what);
    return fmt::format("a list of {}", what);
  };
  switch (key.type) {
    case Type::Float:
      return "a number";
    case Type::Int:
      return key.per_axis ? "an integer or a list of 3 integers" : "an integer";
    case Type::Bool:
      return "true or false";
    case Type::String:
      return "a string";
    case Type::FloatList:
      return count("numbers");
    case Type::IntList:
      return count("integers");
    case Type::Table:
      return "a table";
    case Type::TableList:
      return "an array of tables";
  }
  return {};
}

namespace {
std::string default_text(const Value& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, std::string>) {
          return "\"" + x + "\"";
        } else if constexpr (std::is_same_v<T, bool>) {
          return x ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::vector<double>> ||
                             std::is_same_v<T, std::vector<std::int64_t>>) {
          return fmt::format("[{}]", fmt::join(x, ", "));
        } else {
          return fmt::format("{}", x);
        }
      },
      v);
}
}  // namespace

std::string schema_markdown(const Schema& s) {
  std::ostringstream out;
  out << "# Job file reference\n\n"
         "Generated from the schema by `mpmxdem schema` (a test checks that this file matches "
         "it).\n"
         "A job file is TOML. Every key below is checked: unknown keys, wrong types and values out "
         "of\n"
         "range are errors that name the file, line, key, value and rule. Physical parameters have "
         "no\n"
         "defaults. A number with a unit may be written as a bare number in the unit shown, or as "
         "a\n"
         "string with a unit: `pressure = \"100 kPa\"`, `friction_angle = \"0.5 rad\"`.\n";
  bool in_table = false;
  const char* table_head =
      "| key | type | unit | rule | default | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& k : s.keys) {
    if (k.type == Type::Table || k.type == Type::TableList) {
      in_table = true;
      std::string header = k.path;
      if (header.ends_with("[]")) header.resize(header.size() - 2);
      for (std::size_t pos = 0; (pos = header.find("[]", pos)) != std::string::npos;)
        header.erase(pos, 2);
      out << "\n## " << (k.type == Type::TableList ? "[[" + header + "]]" : "[" + header + "]")
          << "\n\n"
          << k.doc << (k.required ? " Required." : " Optional.") << "\n\n"
          << table_head;
      continue;
    }
    if (!in_table) {
      out << "\n## Top level\n\n" << table_head;
      in_table = true;
    }
    std::string rule = range_rule(k);
    if (!k.choices.empty()) rule = fmt::format("one of {}", fmt::join(k.choices, ", "));
    if (k.min_len > 0 && k.max_len != k.min_len &&
        k.max_len != std::numeric_limits<std::size_t>::max()) {
      rule += fmt::format("{}{} to {} entries", rule.empty() ? "" : "; ", k.min_len, k.max_len);
    }
    const std::string dflt =
        k.required ? "required" : (k.fallback ? default_text(*k.fallback) : "optional");
    out << "| `" << leaf_name(k.path) << "` | " << type_name(k) << " | "
        << canonical_unit(k.quantity) << " | " << rule << " | " << dflt << " | " << k.doc << " |\n";
  }
  return out.str();
}

const Schema& job_schema() {
  static const Schema schema = [] {
    Schema s;
    add_run_sections(s);
    add_dem_sections(s);
    add_mpm_sections(s);
    add_insitu_sections(s);
    return s;
  }();
  return schema;
}

}  // namespace app
