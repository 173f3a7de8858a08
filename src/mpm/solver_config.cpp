// SolverConfig::validate (see solver.hpp): the rules between the knobs, with the job keys' names.
#include <string>

#include "common/errors.hpp"
#include "mpm/messages.hpp"
#include "mpm/solver.hpp"

namespace mpm {

using messages::num_str;
using messages::short_str;

void SolverConfig::validate() const {
  grid.validate();
  common::check_ranges(kSolverConfig, *this);
  if (!gravity.allFinite()) throw common::InputError("mpm.gravity is not finite");
  if (plane_strain_axis < -1 || plane_strain_axis > 2) {
    throw common::InputError(
        "mpm::SolverConfig::plane_strain_axis = " + std::to_string(plane_strain_axis) +
        ": must be -1 (3D) or the thickness axis 0, 1 or 2");
  }
  if (plane_strain_axis >= 0 && grid.cells[plane_strain_axis] != 1) {
    const std::string axis(common::name_of(kPlaneStrainAxisNames, plane_strain_axis));
    throw common::InputError(
        "mpm.plane_strain = \"" + axis + "\": the grid must have exactly 1 cell along " + axis +
        " (mpm.grid.cells), not " + std::to_string(grid.cells[plane_strain_axis]));
  }
  if (plane_strain_axis >= 0 && shape == ShapeKind::bspline2) {
    // uGIMP runs linear through the thickness (its grid basis is the linear hat); the quadratic
    // B-spline's grid basis spans 3 node planes, and a one-cell-thick grid has 2.
    throw common::InputError(std::string("mpm.plane_strain with mpm.shape_function = \"") +
                             std::string(to_string(shape)) +
                             "\": plane strain needs the linear or uGIMP shape functions (the "
                             "B-spline spans 3 node planes, the one-cell-thick grid has 2)");
  }
  if (pic_time > 0.0 && flip != 1.0) {
    throw common::InputError("mpm.pic_time = " + short_str(pic_time) +
                             " s and mpm.flip = " + short_str(flip) +
                             ": the PIC share is set either per step (flip < 1) or in time "
                             "(pic_time > 0, with flip = 1), not both");
  }
  if (pic_time > 0.0 && transfer == Transfer::apic) {
    throw common::InputError("mpm.pic_time = " + short_str(pic_time) +
                             " s with mpm.transfer = \"apic\": the relaxation blends FLIP with "
                             "PIC; APIC has no FLIP part to relax");
  }
  if (xpic_order > 1 && transfer == Transfer::apic) {
    throw common::InputError("mpm.xpic_order = " + std::to_string(xpic_order) +
                             " with mpm.transfer = \"apic\": XPIC shapes the PIC share of the "
                             "FLIP/PIC update; APIC has its own");
  }
  if (xpic_order > 1 && flip == 1.0 && pic_time == 0.0) {
    throw common::InputError("mpm.xpic_order = " + std::to_string(xpic_order) +
                             " with mpm.flip = 1 and no mpm.pic_time: the update has no PIC share "
                             "for XPIC to shape (flip = 0: XPIC alone; flip < 1 or pic_time > 0: "
                             "a blend with FLIP)");
  }
  if ((regularisation_length > 0.0) != (regularisation_modulus > 0.0)) {
    throw common::InputError(
        "mpm.regularisation.length = " + num_str(regularisation_length) +
        " m and mpm.regularisation.modulus = " + num_str(regularisation_modulus) +
        " Pa: the regularisation needs both (> 0), or neither");
  }
  if (formulation == Formulation::total_lagrangian && regularisation_length > 0.0) {
    throw common::InputError(
        "mpm.regularisation with mpm.formulation = \"total_lagrangian\": the nonlocal average "
        "is taken in the current configuration; use the updated Lagrangian formulation");
  }
  if (formulation == Formulation::total_lagrangian && move_points) {
    // The grid is the reference configuration only where the points stay where they started.
    throw common::InputError(
        "mpm.formulation = \"total_lagrangian\" needs mpm.move_points = false (the grid is the "
        "reference configuration only while the points keep their initial positions)");
  }
}

}  // namespace mpm
