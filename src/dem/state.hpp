// Save/load of a whole Simulation as named fields (common::StateWriter/StateReader): spheres,
// cell, Verlet pairs with contact history, counters. A loaded simulation continues bit for bit.
#pragma once

#include <cstdint>
#include <string>

#include "common/state_io.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// Version of the named-field state of a Simulation and of an Rve (field dem/version; history in
/// docs/reference/checkpoint.md). 1: positional parameter arrays; 2: one named field per
/// parameter; 3: of the contact properties only tan_phi (the others follow from the radii); 4: 3
/// with another contact law than CohFrict (params/material/contact_law and the law's parameters),
/// so that a build that knows only CohFrict refused it by its version; 5: every parameter under
/// its job key (the rows of the parameter and choice tables, params/material/young_modulus,
/// rve/params/pressure_floor), params/material/contact_law always. Written: 5; read: 2 to 5 (the
/// older ones under their former names).
inline constexpr std::int64_t kStateVersion = 5;
/// The oldest version read.
inline constexpr std::int64_t kStateVersionOldest = 2;
/// The version that stored a contact law other than CohFrict (as its enumerator), before 5.
inline constexpr std::int64_t kStateVersionOtherLaw = 4;

/// The version of the state under `prefix`. Throws common::InputError naming the field
/// `prefix`dem/version, the version found and the ones this build reads when it reads not that
/// one (or when the field is missing).
std::int64_t check_state_version(const common::StateReader& r, const std::string& prefix = "");

/// Write every field under `prefix` (e.g. "" or "rve/"). Field names:
/// docs/reference/checkpoint.md.
void save_simulation(const Simulation& sim, common::StateWriter& w, const std::string& prefix = "");
/// Rebuild a simulation from fields written by save_simulation. Throws common::InputError
/// naming the field when one is missing or has the wrong size.
[[nodiscard]] Simulation load_simulation(const common::StateReader& r,
                                         const std::string& prefix = "");

}  // namespace dem
