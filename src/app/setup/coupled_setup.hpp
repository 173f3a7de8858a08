// Maps a job with an [mpm] section onto the coupled run of the farm (farm::CoupledConfig): the MPM
// set-up of mpm_setup.hpp, and one micro model per material point: a DEM RVE (material = "dem",
// Duverger et al. 2022 eqs. 11-12) or a linear elastic point (material = "elastic").
#pragma once

#include <cstdint>
#include <string>

#include "app/job/job.hpp"
#include "app/setup/mpm_setup.hpp"
#include "farm/driver.hpp"

namespace app {

/// Run-time choices that do not come from the job file.
struct RunLimits {
  std::string out_dir;          ///< output directory (created by the caller before the run)
  std::int64_t max_steps = -1;  ///< --max-steps: total MPM steps (restart included); <= 0: none
};

/// The coupled run of `job`. DEM RVEs are built lazily, once per rank: the sample of
/// [dem.sample] (a loaded packing re-equilibrated, or a generated cloud compacted; one per sample
/// of the pool of dem.initial_state.samples) is prepared on first use, and so is each in-situ
/// group's RVE that the rank's points need (the sample brought to the group's target stress by
/// dem::reach_stress, app/setup/insitu.hpp); every RVE of the rank starts as a copy of its point's.
/// Throws common::InputError naming the job key when the job cannot be run.
[[nodiscard]] farm::CoupledConfig coupled_setup(const Job& job, const RunLimits& limits);
/// The same from the job's MPM set-up, made by the caller (who also reads it: mpm_setup once).
[[nodiscard]] farm::CoupledConfig coupled_setup(const Job& job, MpmSetup setup,
                                                const RunLimits& limits);

}  // namespace app
