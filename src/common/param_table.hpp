// Parameter tables: one row per member of a plain parameter struct (key, member, unit, range,
// default, meaning), the one home of a setting. Modules declare their tables as plain data; the
// app derives its job schema, the job-to-struct mapping and docs/reference/jobs.md from them, and
// the struct's validate() checks the same ranges and names the same keys.
//
// The default of a row is the struct's default member initializer (read from S{}), so the C++ API
// and the job file cannot disagree on it. A `required` row is a job key without a default (a
// physical parameter): its member initializer is only a placeholder for C++ users.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace common {

/// Physical quantity of a parameter (the job files' app::Quantity is this enum); a bare number is
/// in the unit that unit_symbol() names.
enum class Unit {
  Dimensionless,
  Length,               ///< m
  Pressure,             ///< Pa
  Angle,                ///< deg
  Time,                 ///< s
  Density,              ///< kg/m^3
  Velocity,             ///< m/s
  Acceleration,         ///< m/s^2
  Rate,                 ///< 1/s
  RotationalStiffness,  ///< N m/rad (a moment per radian of relative rotation)
};

/// "m", "Pa", "deg", "s", "kg/m^3", "m/s", "m/s^2", "1/s", "N m/rad"; "" for none.
[[nodiscard]] std::string_view unit_symbol(Unit u);

/// An interval of allowed values; an absent bound is unbounded. NaN and infinities are outside
/// every range.
struct Range {
  std::optional<double> lo;
  std::optional<double> hi;
  bool lo_open = false;  ///< lo itself excluded
  bool hi_open = false;  ///< hi itself excluded

  [[nodiscard]] bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lo && (lo_open ? !(v > *lo) : !(v >= *lo))) return false;
    if (hi && (hi_open ? !(v < *hi) : !(v <= *hi))) return false;
    return true;
  }
  /// The rule in words, as job errors and docs/reference/jobs.md write it: "must be in [0, 90)
  /// deg", "must be > 0 Pa"; "must be a finite number" for an unbounded range.
  [[nodiscard]] std::string rule(Unit u) const;
};

/// Ranges by their shape: gt(a) is (a, inf), in_co(a, b) is [a, b), and so on.
constexpr Range any() { return {}; }
constexpr Range gt(double a) { return {a, std::nullopt, true, false}; }
constexpr Range ge(double a) { return {a, std::nullopt, false, false}; }
constexpr Range in_cc(double a, double b) { return {a, b, false, false}; }
constexpr Range in_co(double a, double b) { return {a, b, false, true}; }
constexpr Range in_oc(double a, double b) { return {a, b, true, false}; }
constexpr Range in_oo(double a, double b) { return {a, b, true, true}; }

/// Where a row's value comes from in a job file.
enum class Source {
  job_default,   ///< optional job key; absent: the struct's default
  job_required,  ///< job key that must be given (physical parameter, no default)
  job_optional,  ///< optional job key without a default value: absent keeps the struct's value,
                 ///< which means "not set" (e.g. mpm.dt: 0, the CFL step)
  cpp_only,      ///< set by the code that builds the struct, not a job key
};

/// One row: a member of S (double, std::int64_t or int) with its job key (relative to the table's
/// section; may contain a dot for a sub-table: "twisting.stiffness"), unit, range, source and
/// meaning.
template <class S>
struct Param {
  std::string_view key;
  std::variant<double S::*, std::int64_t S::*, int S::*> member;
  Unit unit = Unit::Dimensionless;
  Range range;
  Source source = Source::job_default;
  std::string_view doc;

  [[nodiscard]] bool is_integer() const { return member.index() != 0; }
  [[nodiscard]] bool in_job() const { return source != Source::cpp_only; }
  [[nodiscard]] double get(const S& s) const {
    if (const auto* i = std::get_if<1>(&member)) return static_cast<double>(s.**i);
    if (const auto* i = std::get_if<2>(&member)) return static_cast<double>(s.**i);
    return s.*std::get<0>(member);
  }
  /// An integer member's value, exactly (get() goes through a double: 2^53 + 1 would not survive);
  /// 0 for a double member (use get()).
  [[nodiscard]] std::int64_t get_integer(const S& s) const {
    if (const auto* i = std::get_if<1>(&member)) return s.**i;
    if (const auto* i = std::get_if<2>(&member)) return s.**i;
    return 0;
  }
  /// Sets the member; an integer member takes v truncated and clamped to its type's range (a
  /// double at or beyond 2^63 has no int64 value: its conversion would be undefined), an int
  /// member v clamped to the range of int (check_ranges then reports the clamped value); NaN
  /// sets an integer member to 0. Integers from a job go through set_integer, exactly.
  void set(S& s, double v) const {
    if (const auto* i = std::get_if<1>(&member)) {
      constexpr double kTwo63 = 9223372036854775808.0;
      s.** i = std::isnan(v)  ? 0
               : v >= kTwo63  ? std::numeric_limits<std::int64_t>::max()
               : v <= -kTwo63 ? std::numeric_limits<std::int64_t>::min()
                              : static_cast<std::int64_t>(v);
    } else if (const auto* j = std::get_if<2>(&member)) {
      s.** j = std::isnan(v)
                   ? 0
                   : static_cast<int>(std::clamp(v, double{std::numeric_limits<int>::min()},
                                                 double{std::numeric_limits<int>::max()}));
    } else {
      s.*std::get<0>(member) = v;
    }
  }
  /// Sets the member to the integer v exactly (an int member: clamped to the range of int; a
  /// double member: the nearest double).
  void set_integer(S& s, std::int64_t v) const {
    if (const auto* i = std::get_if<1>(&member)) {
      s.** i = v;
    } else if (const auto* j = std::get_if<2>(&member)) {
      s.** j = static_cast<int>(std::clamp<std::int64_t>(v, std::numeric_limits<int>::min(),
                                                         std::numeric_limits<int>::max()));
    } else {
      s.*std::get<0>(member) = static_cast<double>(v);
    }
  }
  /// The default: the member initializer of S.
  [[nodiscard]] double default_value() const {
    static const S defaults{};
    return get(defaults);
  }
};

/// The table of struct S: `type` names S in messages ("dem::Numerics"), `section` is the job table
/// the rows live in ("dem.numerics"). Build it with make_table.
template <class S, std::size_t N>
struct ParamTable {
  std::string_view type;
  std::string_view section;
  std::array<Param<S>, N> rows;

  [[nodiscard]] auto begin() const { return rows.begin(); }
  [[nodiscard]] auto end() const { return rows.end(); }

  /// The full name of a row: the job key ("dem.numerics.verlet_skin"), or for a C++-only row the
  /// member ("dem::RveParams::max_steps_per_call").
  [[nodiscard]] std::string name(const Param<S>& p) const {
    return p.in_job() ? std::string(section) + "." + std::string(p.key)
                      : std::string(type) + "::" + std::string(p.key);
  }
};

/// make_table<S>("dem::Numerics", "dem.numerics", {{row}, {row}, ...}): the row count is deduced.
template <class S, std::size_t N>
constexpr ParamTable<S, N> make_table(std::string_view type, std::string_view section,
                                      const Param<S> (&rows)[N]) {
  ParamTable<S, N> t{type, section, {}};
  for (std::size_t i = 0; i < N; ++i) t.rows[i] = rows[i];
  return t;
}

/// Throws InputError "key = value: rule" (the key as ParamTable::name writes it) for a value
/// outside its range; used by validate() of the tables' structs.
void throw_out_of_range(const std::string& name, double value, bool integer, const Range& range,
                        Unit unit);

/// Checks every row of `table` on `s`: throws InputError naming the first value out of range.
template <class S, std::size_t N>
void check_ranges(const ParamTable<S, N>& table, const S& s) {
  for (const auto& p : table) {
    const double v = p.get(s);
    if (!p.range.contains(v)) throw_out_of_range(table.name(p), v, p.is_integer(), p.range, p.unit);
  }
}

}  // namespace common
