// Job-file schema: every key declares its type, quantity (unit), allowed range, and whether it is
// required or has a default. Validation (job.cpp) and the reference docs/reference/jobs.md both
// come from it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "app/job/units.hpp"
#include "common/choice_table.hpp"

namespace app {

enum class Type { Float, Int, Bool, String, FloatList, IntList, Table, TableList };

/// A resolved value, in the key's canonical unit.
using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>,
                           std::vector<std::int64_t>>;

struct Key {
  std::string path;  ///< full dotted path; elements of table arrays as "mpm.body[].density"
  Type type = Type::Float;
  Quantity quantity = Quantity::Dimensionless;
  std::optional<double> min;  ///< range of a number, or of every list element
  std::optional<double> max;
  bool min_open = false;  ///< min itself excluded
  bool max_open = false;
  std::size_t min_len = 0;  ///< list length bounds
  std::size_t max_len = std::numeric_limits<std::size_t>::max();
  bool required = false;
  std::optional<Value> fallback;     ///< default (numerical and output knobs only)
  std::vector<std::string> choices;  ///< allowed strings
  bool per_axis = false;             ///< an Int that may also be a list of 3 (one per axis)
  std::string doc;                   ///< what the key means

  // Fluent builders keep the schema tables readable.
  Key& in(std::optional<double> lo, std::optional<double> hi, bool lo_open = false,
          bool hi_open = false) {
    min = lo;
    max = hi;
    min_open = lo_open;
    max_open = hi_open;
    return *this;
  }
  Key& len(std::size_t lo, std::size_t hi) {
    min_len = lo;
    max_len = hi;
    return *this;
  }
  Key& need() {
    required = true;
    return *this;
  }
  /// The value is built in place (a Value, or what a Value is made of): moving a Value temporary
  /// into the optional makes GCC 12's -Wmaybe-uninitialized fire (a false positive) under
  /// -fsanitize=address at -O2.
  template <class T>
  Key& or_default(T&& v) {
    fallback.emplace(std::forward<T>(v));
    return *this;
  }
  Key& one_of(std::vector<std::string> c) {
    choices = std::move(c);
    return *this;
  }
  /// The names of a list declared beside its enum (e.g. mpm::kFaceNames), in the list's order:
  /// the one home of the names of a key of an array of tables, which choice_of reads back.
  template <class E, std::size_t N>
  Key& one_of(const std::array<common::Named<E>, N>& names) {
    choices.clear();
    for (const auto& n : names) choices.emplace_back(n.name);
    return *this;
  }
  /// An Int key that also accepts a list of 3 integers, one per axis (Job::per_axis reads both).
  Key& or_per_axis() {
    per_axis = true;
    return *this;
  }
  Key& unit(Quantity q) {
    quantity = q;
    return *this;
  }
};

/// The whole schema, in documentation order. Sections are Table/TableList keys.
struct Schema {
  std::vector<Key> keys;
  std::string section_doc(const std::string& path) const;
  [[nodiscard]] const Key* find(const std::string& path) const;
  /// Keys whose parent is `parent` ("" for the root).
  [[nodiscard]] std::vector<const Key*> children(const std::string& parent) const;

  Key& add(std::string path, Type type, std::string doc) {
    keys.push_back(Key{});
    keys.back().path = std::move(path);
    keys.back().type = type;
    keys.back().doc = std::move(doc);
    return keys.back();
  }
};

/// Parent path of a schema path ("a.b[].c" -> "a.b[]", "a" -> "").
[[nodiscard]] std::string parent_path(const std::string& path);
/// Last component ("a.b[].c" -> "c", "a.b" -> "b").
[[nodiscard]] std::string leaf_name(const std::string& path);
/// The range rule of a key in words ("must be in [0, 90) deg").
[[nodiscard]] std::string range_rule(const Key& key);
/// Human name of a type ("a number", "a list of 3 integers").
[[nodiscard]] std::string type_name(const Key& key);

/// The mpmxdem job schema (sections defined in schema_*.cpp).
[[nodiscard]] const Schema& job_schema();
void add_run_sections(Schema& s);
void add_dem_sections(Schema& s);
void add_mpm_sections(Schema& s);
/// In-situ initial states of DEM bodies (schema_insitu.cpp): after add_mpm_sections.
void add_insitu_sections(Schema& s);

/// docs/reference/jobs.md, generated from the schema.
[[nodiscard]] std::string schema_markdown(const Schema& s);

}  // namespace app
