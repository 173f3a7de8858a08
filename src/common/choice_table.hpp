// Choice tables: the settings that are a name out of a list (a shape function, a stress update,
// where the points move), one row per member of a plain parameter struct, beside the numeric
// parameter tables (param_table.hpp). A row holds the job key, the names and the values they
// stand for, and the meaning; the app derives the job schema (the key, its allowed names, its
// default), docs/reference/jobs.md and the job-to-struct mapping from it, and a module prints a
// member's name with the same row, so a name is written once.
//
// The default of a row is the struct's default member initializer (read from S{}), as for the
// numeric tables; an initializer without a name (plane_strain_axis = -1: 3D) makes the key
// optional, absent keeping it; a row made with required() is a key the job must give. A two-way
// switch the job writes as a TOML boolean (true, false) is a row built with
// flag<&S::member>(key, doc).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace common {

/// A name and the value it stands for (an enumerator, or a bool for a two-way switch).
template <class E>
struct Named {
  std::string_view name;
  E value;
};

/// The name of value v in names; "?" where absent.
template <class E, std::size_t N>
[[nodiscard]] constexpr std::string_view name_of(const std::array<Named<E>, N>& names, E v) {
  for (const auto& n : names) {
    if (n.value == v) return n.name;
  }
  return "?";
}

/// The value that name stands for in names; nullopt where absent.
template <class E, std::size_t N>
[[nodiscard]] constexpr std::optional<E> value_of(const std::array<Named<E>, N>& names,
                                                  std::string_view name) {
  for (const auto& n : names) {
    if (n.name == name) return n.value;
  }
  return std::nullopt;
}

/// The names, as messages write them: "linear, ugimp, bspline2".
template <class E, std::size_t N>
[[nodiscard]] std::string names_list(const std::array<Named<E>, N>& names) {
  std::string s;
  for (const auto& n : names) {
    if (!s.empty()) s += ", ";
    s += n.name;
  }
  return s;
}

/// The most names a row may have.
inline constexpr std::size_t kMaxChoiceNames = 8;

/// One row: a member of S that takes one of a few named values, with its job key (relative to
/// the table's section) and meaning. Build it with choice<&S::member, kNames>(key, doc).
template <class S>
struct Choice {
  std::string_view key;
  std::array<std::string_view, kMaxChoiceNames> names{};
  std::size_t count = 0;
  std::size_t (*index_of)(const S&) = nullptr;  ///< index of the member's value (count: none)
  void (*assign)(S&, std::size_t) = nullptr;    ///< sets the member to the value of names[i]
  std::string_view doc;
  /// A TOML boolean in the job (names "false", "true"; flag()), not a string.
  bool boolean = false;
  /// A job key that must be given (required()): the member initializer is only a placeholder for
  /// C++ users, not a default.
  bool required = false;

  /// The index of name among the names; nullopt where absent.
  [[nodiscard]] std::optional<std::size_t> find(std::string_view name) const {
    for (std::size_t i = 0; i < count; ++i) {
      if (names[i] == name) return i;
    }
    return std::nullopt;
  }
  /// The name of the member's value in s ("?" where the value has no name).
  [[nodiscard]] std::string_view name_in(const S& s) const {
    const std::size_t i = index_of(s);
    return i < count ? names[i] : std::string_view("?");
  }
  /// The default: the name of the member initializer of S ("?" where it has none).
  [[nodiscard]] std::string_view default_name() const {
    static const S defaults{};
    return name_in(defaults);
  }
  /// Whether the member initializer has a name; false: the job key is optional, and absent it
  /// leaves the initializer ("not set").
  [[nodiscard]] bool has_default() const {
    static const S defaults{};
    return index_of(defaults) < count;
  }
};

namespace detail {
template <class M>
struct MemberOf;
template <class S, class E>
struct MemberOf<E S::*> {
  using Struct = S;
  using Value = E;
};
}  // namespace detail

/// The row of member Member (E S::*) with the names Names (a std::array<Named<E>, N> of static
/// storage, e.g. an inline constexpr variable).
template <auto Member, const auto& Names>
constexpr Choice<typename detail::MemberOf<decltype(Member)>::Struct> choice(std::string_view key,
                                                                             std::string_view doc) {
  using S = typename detail::MemberOf<decltype(Member)>::Struct;
  static_assert(Names.size() >= 2 && Names.size() <= kMaxChoiceNames);
  Choice<S> c;
  c.key = key;
  c.doc = doc;
  c.count = Names.size();
  for (std::size_t i = 0; i < Names.size(); ++i) c.names[i] = Names[i].name;
  c.index_of = [](const S& s) -> std::size_t {
    for (std::size_t i = 0; i < Names.size(); ++i) {
      if (Names[i].value == s.*Member) return i;
    }
    return Names.size();
  };
  c.assign = [](S& s, std::size_t i) { s.*Member = Names[i].value; };
  return c;
}

/// The names of a two-way switch written as a TOML boolean.
inline constexpr std::array<Named<bool>, 2> kBoolNames{{{"false", false}, {"true", true}}};

/// The row of a bool member Member (bool S::*) that the job writes as a TOML boolean: its names
/// are "false" and "true", its default the member initializer.
template <auto Member>
constexpr Choice<typename detail::MemberOf<decltype(Member)>::Struct> flag(std::string_view key,
                                                                           std::string_view doc) {
  static_assert(std::is_same_v<typename detail::MemberOf<decltype(Member)>::Value, bool>);
  auto c = choice<Member, kBoolNames>(key, doc);
  c.boolean = true;
  return c;
}

/// Row c as a job key that must be given, without a default (a setting that has none, such as the
/// loading programme of a DEM test); the member initializer is a placeholder for C++ users.
template <class S>
constexpr Choice<S> required(Choice<S> c) {
  c.required = true;
  return c;
}

/// The choice rows of struct S in job section `section` ("mpm").
template <class S, std::size_t N>
struct ChoiceTable {
  std::string_view section;
  std::array<Choice<S>, N> rows;

  [[nodiscard]] auto begin() const { return rows.begin(); }
  [[nodiscard]] auto end() const { return rows.end(); }
  /// The job key of a row: "mpm.shape_function".
  [[nodiscard]] std::string name(const Choice<S>& c) const {
    return std::string(section) + "." + std::string(c.key);
  }
  /// The row of `key` (relative to the section); nullptr where absent.
  [[nodiscard]] const Choice<S>* row(std::string_view key) const {
    for (const auto& c : rows) {
      if (c.key == key) return &c;
    }
    return nullptr;
  }
};

}  // namespace common
