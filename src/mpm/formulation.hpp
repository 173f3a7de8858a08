// Formulation of the point kinematics (docs/design/mpm.md, "Total Lagrangian formulation"): updated
// Lagrangian (classical MPM: the grid is the current configuration) or total Lagrangian (the
// grid is the reference configuration: only with points that do not move, where the grid is
// indeed where the material was at the start).
#pragma once

#include <string_view>
#include <vector>

#include "common/choice_table.hpp"
#include "common/types.hpp"

namespace mpm {

enum class Formulation {
  updated_lagrangian,  ///< L = sum_v V_v (x) grad S_v, forces V sigma grad S (the default)
  total_lagrangian,    ///< grad S maps through F^-T: L = Fdot F^-1, forces V sigma F^-T grad S
};
/// The job's names (mpm.formulation).
inline constexpr std::array<common::Named<Formulation>, 2> kFormulationNames{
    {{"updated_lagrangian", Formulation::updated_lagrangian},
     {"total_lagrangian", Formulation::total_lagrangian}}};

/// "updated_lagrangian" or "total_lagrangian"; throws common::InputError otherwise.
[[nodiscard]] Formulation formulation_from_string(std::string_view name);
[[nodiscard]] std::string_view to_string(Formulation f);

/// Total Lagrangian velocity gradient: the grid gradient of the velocity is the rate of the
/// deformation gradient, Fdot = sum_v V_v (x) grad_X S_v, so L = Fdot F^-1 (F at the start of
/// the step): L[p] <- L[p] F[p]^-1. Pre: same sizes, F invertible.
void to_spatial_gradient(const std::vector<common::Mat3>& F, std::vector<common::Mat3>& L);

/// The tensor whose product with grad_X S gives the spatial internal force: V sigma grad_x S =
/// V sigma F^-T grad_X S (= V0 P grad_X S, P the first Piola-Kirchhoff stress): out[p] =
/// stress[p] F[p]^-T. Pre: same sizes, F invertible.
void stress_for_reference_gradient(const std::vector<common::Mat3>& F,
                                   const std::vector<common::Mat3>& stress,
                                   std::vector<common::Mat3>& out);

}  // namespace mpm
