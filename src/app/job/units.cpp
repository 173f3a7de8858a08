// Unit table and "<number> <unit>" parsing for job files: see units.hpp.
#include "app/job/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>

namespace app {

namespace {
struct UnitDef {
  Quantity q;
  std::string_view name;
  double factor;  // value in canonical unit = number * factor
};

constexpr std::array kUnits{
    UnitDef{Quantity::Length, "m", 1.0},
    UnitDef{Quantity::Length, "cm", 1e-2},
    UnitDef{Quantity::Length, "mm", 1e-3},
    UnitDef{Quantity::Length, "um", 1e-6},
    UnitDef{Quantity::Pressure, "Pa", 1.0},
    UnitDef{Quantity::Pressure, "kPa", 1e3},
    UnitDef{Quantity::Pressure, "MPa", 1e6},
    UnitDef{Quantity::Pressure, "GPa", 1e9},
    UnitDef{Quantity::Angle, "deg", 1.0},
    UnitDef{Quantity::Angle, "rad", 180.0 / std::numbers::pi},
    UnitDef{Quantity::Time, "s", 1.0},
    UnitDef{Quantity::Time, "ms", 1e-3},
    UnitDef{Quantity::Time, "us", 1e-6},
    UnitDef{Quantity::Time, "min", 60.0},
    UnitDef{Quantity::Time, "h", 3600.0},
    UnitDef{Quantity::Density, "kg/m^3", 1.0},
    UnitDef{Quantity::Density, "kg/m3", 1.0},
    UnitDef{Quantity::Density, "g/cm^3", 1e3},
    UnitDef{Quantity::Velocity, "m/s", 1.0},
    UnitDef{Quantity::Velocity, "mm/s", 1e-3},
    UnitDef{Quantity::Acceleration, "m/s^2", 1.0},
    UnitDef{Quantity::Acceleration, "m/s2", 1.0},
    UnitDef{Quantity::Rate, "1/s", 1.0},
    UnitDef{Quantity::RotationalStiffness, "N m/rad", 1.0},
    UnitDef{Quantity::RotationalStiffness, "N*m/rad", 1.0},
    UnitDef{Quantity::RotationalStiffness, "uN m/rad", 1e-6},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}
}  // namespace

std::string_view canonical_unit(Quantity q) { return common::unit_symbol(q); }

std::string_view quantity_name(Quantity q) {
  switch (q) {
    case Quantity::Dimensionless:
      return "a dimensionless number";
    case Quantity::Length:
      return "a length";
    case Quantity::Pressure:
      return "a pressure";
    case Quantity::Angle:
      return "an angle";
    case Quantity::Time:
      return "a time";
    case Quantity::Density:
      return "a density";
    case Quantity::Velocity:
      return "a velocity";
    case Quantity::Acceleration:
      return "an acceleration";
    case Quantity::Rate:
      return "a rate";
    case Quantity::RotationalStiffness:
      return "a rotational stiffness";
  }
  return "";
}

std::string accepted_units(Quantity q) {
  std::string out;
  for (const auto& u : kUnits) {
    if (u.q != q) continue;
    if (!out.empty()) out += ", ";
    out += u.name;
  }
  return out;
}

std::optional<double> parse_quantity(std::string_view text, Quantity q, std::string& why) {
  const std::string_view s = trim(text);
  double number = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), number);
  if (ec != std::errc() || end == s.data()) {
    why = "must be a number or a string \"<number> <unit>\"";
    return std::nullopt;
  }
  if (!std::isfinite(number)) {
    why = "must be finite";
    return std::nullopt;
  }
  const std::string_view unit =
      trim(std::string_view(end, static_cast<std::size_t>(s.data() + s.size() - end)));
  if (q == Quantity::Dimensionless) {
    why = "is dimensionless: write a plain number, without a unit";
    return std::nullopt;
  }
  if (unit.empty()) {
    why = "needs a unit when written as a string (" + accepted_units(q) + ")";
    return std::nullopt;
  }
  for (const auto& u : kUnits) {
    if (u.name == unit) {
      if (u.q != q) {
        why = "unit '" + std::string(unit) + "' is not " + std::string(quantity_name(q)) +
              "; use " + accepted_units(q);
        return std::nullopt;
      }
      return number * u.factor;
    }
  }
  why = "unknown unit '" + std::string(unit) + "'; use " + accepted_units(q);
  return std::nullopt;
}

}  // namespace app
