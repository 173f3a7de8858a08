// Maps the [dem.*] sections of a job onto the dem module's parameter structs, and builds the
// prepared sample (a loaded packing re-equilibrated, or a generated cloud compacted).
#pragma once

#include <string>
#include <vector>

#include "app/job/job.hpp"
#include "dem/loading.hpp"
#include "dem/params.hpp"
#include "dem/simulation.hpp"

namespace app {

[[nodiscard]] dem::Material dem_material(const Job& job);
[[nodiscard]] dem::Numerics dem_numerics(const Job& job);
[[nodiscard]] dem::Preparation dem_preparation(const Job& job);
/// The loading programme of [dem.loading] (its choice rows, dem::kLoadingChoices); the job has
/// the section (the schema requires its type).
[[nodiscard]] dem::LoadingProgramme dem_loading(const Job& job);
/// The packing of [dem.sample]: read (path relative to the job file) or generated as a cloud.
/// `generated` tells which. `sample` k > 0 (the pool of dem.initial_state.samples, generated
/// clouds only) uses the seed dem.sample.seed + k.
[[nodiscard]] dem::Packing dem_packing(const Job& job, bool& generated, std::int64_t sample = 0);
/// Median diameter by mass d50 [m]: of the PSD table, or of the packing's spheres.
[[nodiscard]] double dem_d50(const Job& job, const dem::Packing& packing);
/// A prepared simulation: generated clouds are compacted (lowered friction, restored, then
/// re-equilibrated); loaded packings are re-equilibrated at the preparation pressure (their
/// tangential forces are not stored). Logs what it did, or appends its two lines to `lines`
/// when given (preparations on several threads log in order afterwards; the progress lines of
/// a long preparation are logged as they come). `sample`: see dem_packing. Prepared with the
/// fixed skin (dem::FixedSkinScope); the job's adaptive skin applies to what follows.
[[nodiscard]] dem::Simulation prepared_sample(const Job& job, std::int64_t sample = 0,
                                              std::vector<std::string>* lines = nullptr);

}  // namespace app
