// Maps the [mpm] sections of a job onto the mpm module: solver configuration, material points of
// every body, velocity constraints and tractions.
#pragma once

#include <string>
#include <vector>

#include "app/job/job.hpp"
#include "mpm/boundary.hpp"
#include "mpm/material_points.hpp"
#include "mpm/solver.hpp"

namespace app {

/// Material index of the points: kElastic for bodies with material = "elastic", kDem for "dem".
inline constexpr std::int32_t kElasticMaterial = 0;
inline constexpr std::int32_t kDemMaterial = 1;

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

/// Axis (0..2) and side (-1, +1) of a face name "x-", ..., "z+".
void face_axis_side(const std::string& face, int& axis, int& side);

}  // namespace app
