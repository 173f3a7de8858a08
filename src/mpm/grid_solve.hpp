// Grid solve: nodal velocities from momentum and accelerations with Cundall damping
// (Duverger et al. 2022, eq. 8), with a small-mass threshold.
#pragma once

#include <array>

#include "common/choice_table.hpp"
#include "mpm/grid.hpp"

namespace mpm {

/// How the damping force of eq. 8 is formed (docs/design/mpm.md, "Damping").
enum class DampingMode {
  /// Eq. 8 as written: a = (f - D |f| V / |V|) / m, one vector norm per node.
  cundall_vector,
  /// Per component, as YADE/PFC's local non-viscous damping: a_k = (f_k - D |f_k| sign(V_k)) / m.
  cundall_component,
};
/// The job's names (mpm.damping_mode).
inline constexpr std::array<common::Named<DampingMode>, 2> kDampingModeNames{
    {{"vector", DampingMode::cundall_vector}, {"component", DampingMode::cundall_component}}};

/// Mean nodal mass over the active nodes [kg] (0 when none).
double typical_nodal_mass(const GridFields& fields);

/// V_v = momentum_v / m_v on active nodes with m_v >= threshold [kg]; V_v = 0 below it.
void compute_nodal_velocity(double threshold, GridFields& fields);

/// a_v from eq. 8 with damping ratio D [-] on active nodes with m_v >= threshold; a_v = 0 below.
/// V in the damping term is fields.velocity (the start-of-step nodal velocity, constrained).
/// Components flagged in fields.fixed are left out of both |f| and V in the damping term (their
/// acceleration is then overwritten by apply_acceleration_constraints).
void compute_nodal_acceleration(double threshold, double damping, DampingMode mode,
                                GridFields& fields);

}  // namespace mpm
