// Maps the [mpm] sections of a job onto the mpm module: solver configuration, material points of
// every body, velocity constraints and tractions.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "app/job/job.hpp"
#include "common/choice_table.hpp"
#include "mpm/boundary.hpp"
#include "mpm/material_points.hpp"
#include "mpm/solver.hpp"

namespace app {

/// Material index of the points: kElastic for bodies with material = "elastic", kDem for "dem".
inline constexpr std::int32_t kElasticMaterial = 0;
inline constexpr std::int32_t kDemMaterial = 1;
/// The job's names of the material indices (mpm.body[].material).
inline constexpr std::array<common::Named<std::int32_t>, 2> kBodyMaterialNames{
    {{"dem", kDemMaterial}, {"elastic", kElasticMaterial}}};

struct MpmSetup {
  mpm::SolverConfig config;
  mpm::MaterialPoints points;  ///< every body's points, stresses set to the body's initial stress
  std::vector<std::int32_t> body;  ///< index b of mpm.body[b] of each point
  std::vector<mpm::VelocityConstraint> constraints;
  std::vector<mpm::TractionLoad> tractions;
  bool has_elastic = false;
  bool has_dem = false;
  common::Mat3 elastic_initial_stress = common::Mat3::Zero();  ///< [Pa], of the elastic bodies
  double end_time = 0.0;                                       ///< [s]
};

/// Throws common::InputError (naming the job key) when the job is inconsistent with the grid.
[[nodiscard]] MpmSetup mpm_setup(const Job& job);

}  // namespace app
