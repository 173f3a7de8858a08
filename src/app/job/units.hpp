// Physical quantities and the units a job file may write them in ("100 kPa", "30 deg").
// A bare number is read in the quantity's canonical unit (SI, but degrees for angles).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "common/param_table.hpp"

namespace app {

/// A job key's quantity: the parameter tables' unit (one enum for both).
using Quantity = common::Unit;

/// The unit a bare number is read in ("Pa", "deg", "" for dimensionless): common::unit_symbol.
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
