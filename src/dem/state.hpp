// Save/load of a whole Simulation as named fields (common::StateWriter/StateReader): spheres,
// cell, Verlet pairs with contact history, counters. A loaded simulation continues bit for bit.
#pragma once

#include <string>

#include "common/state_io.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// Write every field under `prefix` (e.g. "" or "rve/"). Field names: see docs/dem.md.
void save_simulation(const Simulation& sim, common::StateWriter& w, const std::string& prefix = "");
/// Rebuild a simulation from fields written by save_simulation. Throws common::InputError
/// naming the field when one is missing or has the wrong size.
[[nodiscard]] Simulation load_simulation(const common::StateReader& r,
                                         const std::string& prefix = "");

}  // namespace dem
