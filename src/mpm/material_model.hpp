// The seam between MPM and any constitutive model, the DEM farm included (docs/design/mpm.md, "Seam").
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>

#include "common/types.hpp"

namespace mpm {

/// Batched constitutive model. Convention at the seam (written once, here): L is the full
/// velocity gradient dv/dx (1/s, spin included), stress is Cauchy, Pa, TENSION POSITIVE.
/// State is not part of the seam: the owner of a model knows its concrete type and checkpoints
/// it with that type's save/load (LinearElastic::save; the farm's collective checkpoint), as
/// Solver::save does for the points (docs/reference/checkpoint.md, "One state protocol").
class MaterialModel {
 public:
  virtual ~MaterialModel() = default;
  /// For every point p (ids[p] are stable point ids): advance the state by dt (s) under L[p]
  /// and write the new Cauchy stress into stress[p].
  /// @pre ids.size() == L.size() == stress.size(); dt > 0.
  virtual void update_stress(std::span<const std::int64_t> ids, std::span<const common::Mat3> L,
                             double dt, std::span<common::Mat3> stress) = 0;
  /// Largest elastic wave speed (m/s) for a CFL time step.
  virtual double wave_speed() const = 0;
  /// For the points of the last update_stress call (`ids` as given there, in that order):
  /// dilute[p] = 1 where the point's material is, after that update, a dilute material whose
  /// volume carries no lasting force (a spray of grains that collide now and then), 0 elsewhere.
  /// The solver's blow-up bound on a point's volume does not apply to those
  /// (docs/design/rve_step.md, "An RVE without contacts"). Default: no point is.
  /// @pre ids.size() == dilute.size()
  virtual void mark_dilute(std::span<const std::int64_t> ids,
                           std::span<std::uint8_t> dilute) const {
    (void)ids;
    std::fill(dilute.begin(), dilute.end(), std::uint8_t{0});
  }
};

}  // namespace mpm
