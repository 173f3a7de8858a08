// Maps a job with an [mpm] section onto the coupled run of the farm (farm::CoupledConfig): the MPM
// set-up of mpm_setup.hpp, and one micro model per material point: a DEM RVE (material = "dem",
// Duverger et al. 2022 eqs. 11-12) or a linear elastic point (material = "elastic").
#pragma once

#include <cstdint>
#include <string>

#include "app/job.hpp"
#include "farm/driver.hpp"

namespace app {

/// Run-time choices that do not come from the job file.
struct RunLimits {
  std::string out_dir;          ///< output directory (created by the caller before the run)
  std::int64_t max_steps = -1;  ///< --max-steps: total MPM steps (restart included); <= 0: none
};

/// The coupled run of `job`. DEM RVEs are built lazily, once per rank: the sample of
/// [dem.sample] (a loaded packing re-equilibrated, or a generated cloud compacted) is prepared on
/// the first call and every RVE of the rank starts as a copy of it. Throws common::InputError
/// naming the job key when the job cannot be run.
[[nodiscard]] farm::CoupledConfig coupled_setup(const Job& job, const RunLimits& limits);

}  // namespace app
