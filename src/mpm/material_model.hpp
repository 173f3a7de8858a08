// The seam between MPM and any constitutive model, the DEM farm included (docs/mpm.md, "Seam").
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "common/state_io.hpp"
#include "common/types.hpp"

namespace mpm {

/// Batched constitutive model. Convention at the seam (written once, here): L is the full
/// velocity gradient dv/dx (1/s, spin included), stress is Cauchy, Pa, TENSION POSITIVE.
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

  /// Added member: writes the model's own state (e.g. its stresses) under `prefix`, for a
  /// checkpoint. Default: nothing (a stateless model, or one checkpointed by its owner, as the
  /// DEM farm does).
  virtual void write_state(common::StateWriter& /*writer*/, std::string_view /*prefix*/) const {}
  /// Added member: reads back what write_state wrote. Default: nothing.
  virtual void read_state(const common::StateReader& /*reader*/, std::string_view /*prefix*/) {}
};

}  // namespace mpm
