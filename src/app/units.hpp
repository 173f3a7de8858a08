// Physical quantities and the units a job file may write them in ("100 kPa", "30 deg").
// A bare number is read in the quantity's canonical unit (SI, but degrees for angles).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace app {

enum class Quantity {
  Dimensionless,
  Length,        ///< m
  Pressure,      ///< Pa
  Angle,         ///< deg
  Time,          ///< s
  Density,       ///< kg/m^3
  Velocity,      ///< m/s
  Acceleration,  ///< m/s^2
  Rate,          ///< 1/s
};

/// The unit a bare number is read in ("Pa", "deg", "" for dimensionless).
[[nodiscard]] std::string_view canonical_unit(Quantity q);
/// Human name of the quantity ("a pressure").
[[nodiscard]] std::string_view quantity_name(Quantity q);
/// The units accepted for q, for messages and docs ("Pa, kPa, MPa, GPa").
[[nodiscard]] std::string accepted_units(Quantity q);

/// Parses "<number> <unit>" into the canonical unit of q. On failure returns nullopt and sets
/// `why` to the rule that was broken.
[[nodiscard]] std::optional<double> parse_quantity(std::string_view text, Quantity q,
                                                   std::string& why);

}  // namespace app
