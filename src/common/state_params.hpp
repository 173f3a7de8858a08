// Parameter and choice tables (param_table.hpp, choice_table.hpp) in a state (checkpoint): every
// row is a one-value field named by the row's key under a directory, so that a checkpoint names a
// setting as the job file does ("params/numerics/verlet_skin" for dem.numerics.verlet_skin). A
// C++-only row's key is its one name too. docs/reference/checkpoint.md lists the fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "common/choice_table.hpp"
#include "common/errors.hpp"
#include "common/param_table.hpp"
#include "common/state_io.hpp"

namespace common {

/// The field of row key `key` under `dir`: a dot (a job sub-table) becomes a '/', so that
/// "twisting.stiffness" under "params/material/" is "params/material/twisting/stiffness".
[[nodiscard]] inline std::string state_field(std::string_view dir, std::string_view key) {
  std::string name(dir);
  for (const char c : key) name += c == '.' ? '/' : c;
  return name;
}

/// A field of an older state version that a row is read from: its name then, relative to the
/// directory, when that was not the row's key (a C++ member's name, "young" for young_modulus),
/// or a field that some older states lack. The rows of a table without such an entry are read
/// under their key.
struct FormerField {
  std::string_view key;        ///< the row's key
  std::string_view name;       ///< the field's name in the older version, relative to the directory
  bool may_be_absent = false;  ///< absent in some older states: the member keeps its value
};

/// Writes every row of `table` (C++-only rows included) as a field of one value under `dir`: an
/// int64 for an integer member, a double otherwise.
template <class S, std::size_t N>
void write_params(StateWriter& w, std::string_view dir, const ParamTable<S, N>& table, const S& s) {
  for (const auto& p : table) {
    const std::string name = state_field(dir, p.key);
    if (p.is_integer()) {
      write_scalar(w, name, p.get_integer(s));
    } else {
      write_scalar(w, name, p.get(s));
    }
  }
}

/// Reads every row of `table` from the fields write_params wrote under `dir`, or, with `former`
/// (an older version), from the fields that version wrote: a row with entries in `former` is
/// read from the first of their fields present (in their order), other rows under their key.
/// Throws InputError naming the field (`what`: "dem state") when one is missing, is not of one
/// value of the row's type, or holds a number that is not finite; ranges are validate()'s.
template <class S, std::size_t N>
void read_params(const StateReader& r, std::string_view dir, const ParamTable<S, N>& table, S& s,
                 std::string_view what, std::span<const FormerField> former = {}) {
  for (const auto& p : table) {
    std::string name = state_field(dir, p.key);
    bool listed = false;
    bool may_be_absent = false;
    std::string found;
    for (const FormerField& f : former) {
      if (f.key != p.key) continue;
      const std::string candidate = state_field(dir, f.name);
      if (!listed) name = candidate;  // the name a missing field is reported under
      listed = true;
      may_be_absent = may_be_absent || f.may_be_absent;
      if (found.empty() && r.has(candidate)) found = candidate;
    }
    if (found.empty()) {
      if (may_be_absent) continue;
      found = name;  // not there: the read below names it
    }
    if (p.is_integer()) {
      p.set_integer(s, read_scalar_i64(r, found));
    } else {
      const double v = read_scalar_f64(r, found);
      require_finite(std::span<const double>(&v, 1), std::string(what) + ": field '" + found + "'");
      p.set(s, v);
    }
  }
}

/// Writes every row of the choice table as an int64 field of one value under `dir`: the index of
/// the member's name in the row's names (their order is the encoding: a row's names are appended
/// to, never reordered), or -1 for a member initializer without a name ("not set").
template <class S, std::size_t N>
void write_choices(StateWriter& w, std::string_view dir, const ChoiceTable<S, N>& table,
                   const S& s) {
  for (const auto& c : table) {
    const std::size_t i = c.index_of(s);
    write_scalar(w, state_field(dir, c.key),
                 i < c.count ? static_cast<std::int64_t>(i) : std::int64_t{-1});
  }
}

/// Reads every row of the choice table from the fields write_choices wrote under `dir`. Throws
/// InputError naming the field and the names (`what`: "dem state") for an index that is not one
/// of the row's names (-1 only where the member initializer has no name: it is kept).
template <class S, std::size_t N>
void read_choices(const StateReader& r, std::string_view dir, const ChoiceTable<S, N>& table, S& s,
                  std::string_view what) {
  for (const auto& c : table) {
    const std::string name = state_field(dir, c.key);
    const std::int64_t i = read_scalar_i64(r, name);
    if (i == -1 && !c.has_default()) continue;
    if (i < 0 || i >= static_cast<std::int64_t>(c.count)) {
      std::string names;
      for (std::size_t k = 0; k < c.count; ++k) {
        names += (k > 0 ? ", " : "") + std::to_string(k) + " (" + std::string(c.names[k]) + ")";
      }
      throw InputError(std::string(what) + ": field '" + name + "' = " + std::to_string(i) +
                       ": must be one of " + names);
    }
    c.assign(s, static_cast<std::size_t>(i));
  }
}

}  // namespace common
