// Test helper: a DEM state of today (version 5) written as versions 2 to 4 wrote it, the
// parameters under the C++ members' names of then and the choices as the flags of then. The
// names are written out here, not taken from the code's tables (docs/reference/checkpoint.md,
// version history), so that a test of the former names checks the code against them.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "common/state_store.hpp"

namespace dem_test {

/// `s` (written by dem::save_simulation or dem::Rve::save) as a state of `version` (2, 3 or 4;
/// 4 only with another contact law than CohFrict) wrote it.
inline common::StateStore as_former_version(const common::StateStore& s, std::int64_t version) {
  const std::map<std::string, std::string> renamed{
      {"params/material/young_modulus", "params/material/young"},
      {"params/material/friction_angle", "params/material/friction_deg"},
      {"params/material/stiffness_ratio", "params/material/ks_over_kn"},
      {"params/material/rolling_stiffness", "params/material/alpha_r"},
      {"params/material/rolling_strength", "params/material/eta_r"},
      {"params/material/twisting/stiffness", "params/material/alpha_t"},
      {"params/material/twisting/strength", "params/material/eta_t"},
      {"params/material/hertz_mindlin/poisson_ratio", "params/material/hertz_mindlin/poisson"},
      {"params/material/hertz_mindlin/rolling_stiffness", "params/material/hertz_mindlin/krot"},
      {"params/material/hertz_mindlin/rolling_strength", "params/material/hertz_mindlin/eta"},
      {"params/material/hertz_mindlin/twisting_stiffness", "params/material/hertz_mindlin/ktwist"},
      {"params/numerics/timestep_safety", "params/numerics/dt_safety"},
      {"params/numerics/verlet_skin", "params/numerics/skin_factor"},
      {"params/numerics/verlet_skin_min", "params/numerics/skin_min_factor"},
      {"rve/params/inertial_number", "rve/inertial_number"},
      {"rve/params/d50", "rve/d50"},
      {"rve/params/pressure_floor", "rve/p_floor"},
      {"rve/params/max_strain_per_step", "rve/max_strain_per_step"},
      {"rve/params/max_steps_per_call", "rve/max_steps_per_call"},
      {"rve/params/initial_pressure", "rve/initial_pressure"},
      {"rve/params/dt_refresh", "rve/dt_refresh"},
      {"rve/params/disconnect_fraction", "rve/disconnect_fraction"},
      {"rve/params/min_dem_steps", "rve/min_dem_steps"},
      {"rve/params/end_forces", "rve/carry_end_forces"},  // 1: carried, as today
      {"rve/params/free_flight", "rve/free_flight"},      // 1: one_step, as today
      {"rve/params/rate", "rve/rate"},                    // flipped: then 1 was material
      {"rve/params/contact_loss", "rve/contact_loss"},    // flipped: then 1 was disconnected
  };
  common::StateStore out;
  for (const auto& [name, field] : s.fields()) {
    if (name == "dem/version") {
      out.write(name, std::span<const std::int64_t>(std::vector<std::int64_t>{version}));
      continue;
    }
    // Version 4 alone stored the law (its enumerator: 1, Hertz-Mindlin); 2 and 3 were CohFrict.
    if (name == "params/material/contact_law" && version != 4) continue;
    const auto it = renamed.find(name);
    const std::string old = it == renamed.end() ? name : it->second;
    if (name == "rve/params/rate" || name == "rve/params/contact_loss") {
      const std::int64_t v = std::get<1>(field).at(0);
      out.write(old, std::span<const std::int64_t>(std::vector<std::int64_t>{1 - v}));
      continue;
    }
    std::visit([&](const auto& v) { out.write(old, std::span(v.data(), v.size())); }, field);
  }
  return out;
}

}  // namespace dem_test
