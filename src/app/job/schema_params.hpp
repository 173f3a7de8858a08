// Parameter and choice tables of the modules (common/param_table.hpp, common/choice_table.hpp) in
// the job schema: their rows become schema keys, and a validated job fills their structs. The key,
// unit, range or names, default and meaning of such a setting are written once, in its module's
// table.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "app/job/job.hpp"
#include "app/job/schema.hpp"
#include "common/choice_table.hpp"
#include "common/errors.hpp"
#include "common/param_table.hpp"

namespace app {

/// The sub-table of a row's key within its table's section: "twisting" for "twisting.stiffness",
/// "" for "stiffness".
[[nodiscard]] inline std::string_view sub_table_of(std::string_view key) {
  const auto dot = key.rfind('.');
  return dot == std::string_view::npos ? std::string_view() : key.substr(0, dot);
}

/// Adds the job rows of `table` whose key lies in sub-table `sub` of the table's section ("" for
/// the section itself, "twisting" for "twisting.stiffness") as schema keys, in table order. The
/// caller adds the section (and sub-table) keys themselves, with their documentation. With
/// `required_when` (e.g. "with contact_law = \"cohfrict\""), the required rows are required by a
/// job rule (app/job/job_rules.cpp) under that condition, not by the schema, and their
/// documentation says when.
template <class S, std::size_t N>
void add_params(Schema& s, const common::ParamTable<S, N>& table, std::string_view sub = {},
                std::string_view required_when = {}) {
  for (const auto& p : table) {
    if (!p.in_job() || sub_table_of(p.key) != sub) continue;
    Key& k = s.add(table.name(p), p.is_integer() ? Type::Int : Type::Float, std::string(p.doc))
                 .unit(p.unit)
                 .in(p.range.lo, p.range.hi, p.range.lo_open, p.range.hi_open);
    if (p.source == common::Source::job_required && !required_when.empty()) {
      k.doc += " Required " + std::string(required_when) + ".";
    } else if (p.source == common::Source::job_required) {
      k.need();
    } else if (p.source == common::Source::job_optional) {
      continue;  // absent: the struct keeps its "not set" value
    } else if (p.is_integer()) {
      k.or_default(static_cast<std::int64_t>(p.default_value()));
    } else {
      k.or_default(p.default_value());
    }
  }
}

/// Sets every member of `s` whose job key `job` holds (a defaulted key holds the table's default);
/// absent optional keys and C++-only rows keep their value in `s`.
template <class S, std::size_t N>
void fill_from_job(const Job& job, const common::ParamTable<S, N>& table, S& s) {
  for (const auto& p : table) {
    if (!p.in_job()) continue;
    const std::string key = table.name(p);
    if (!job.has(key)) continue;
    // An integer exactly: through a double, 2^63 - 1 became 2^63, whose conversion back is
    // undefined (it gave -2^63: "output.every = -9223372036854775808: must be >= 1").
    if (p.is_integer()) {
      p.set_integer(s, job.integer(key));
    } else {
      p.set(s, job.number(key));
    }
  }
}

/// Adds the rows of a choice table whose key lies in sub-table `sub` of the table's section (as
/// add_params) as schema keys, in table order: a string key whose names are the allowed values,
/// or a boolean (common::flag rows); the struct's member initializer names the default, a
/// member initializer without a name makes the key optional, and a common::required row is a key
/// the job must give.
template <class S, std::size_t N>
void add_choices(Schema& s, const common::ChoiceTable<S, N>& table, std::string_view sub = {}) {
  for (const auto& c : table) {
    if (sub_table_of(c.key) != sub) continue;
    if (c.boolean) {
      s.add(table.name(c), Type::Bool, std::string(c.doc)).or_default(c.default_name() == "true");
      continue;
    }
    Key& k = s.add(table.name(c), Type::String, std::string(c.doc))
                 .one_of(std::vector<std::string>(
                     c.names.begin(), c.names.begin() + static_cast<std::ptrdiff_t>(c.count)));
    if (c.required) {
      k.need();
    } else if (c.has_default()) {
      k.or_default(std::string(c.default_name()));
    }
  }
}

/// Sets every member of `s` that a row of the choice table names, from the job (a defaulted key
/// holds the default's name; an absent optional key leaves the member). The schema has checked
/// the names; a name the row lacks (a schema and table out of step) throws common::InputError
/// naming the key.
template <class S, std::size_t N>
void fill_choices_from_job(const Job& job, const common::ChoiceTable<S, N>& table, S& s) {
  for (const auto& c : table) {
    const std::string key = table.name(c);
    if (!job.has(key)) continue;
    const std::string name =
        c.boolean ? std::string(job.flag(key) ? "true" : "false") : job.text(key);
    const auto i = c.find(name);
    if (!i) throw common::InputError(job.message(key, "is not one of the names of this setting"));
    c.assign(s, *i);
  }
}

/// The value that string key `key` of the job names in `names` (the list its schema key takes
/// with Key::one_of, e.g. a key of an array of tables: mpm.body[0].material). The schema has
/// checked the name; a name the list lacks (a schema and list out of step) throws
/// common::InputError naming the key. The key must be in the job.
template <class E, std::size_t N>
[[nodiscard]] E choice_of(const Job& job, const std::string& key,
                          const std::array<common::Named<E>, N>& names) {
  const auto v = common::value_of(names, job.text(key));
  if (!v) throw common::InputError(job.message(key, "is not one of the names of this setting"));
  return *v;
}

/// As above, with `fallback` where the job has no key `key` (an optional key).
template <class E, std::size_t N>
[[nodiscard]] E choice_of(const Job& job, const std::string& key,
                          const std::array<common::Named<E>, N>& names, E fallback) {
  return job.has(key) ? choice_of(job, key, names) : fallback;
}

/// True when the job file gives `key` (not a default the schema filled in).
[[nodiscard]] inline bool written(const Job& job, const std::string& key) {
  const auto it = job.entries().find(key);
  return it != job.entries().end() && !it->second.defaulted && it->second.line > 0;
}

}  // namespace app
