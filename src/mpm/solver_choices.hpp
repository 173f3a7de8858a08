// [mpm]: the settings of SolverConfig that are a name out of a list (the shape function, the
// stress update, the transfer, the plane-strain axis, ...) or a switch (move_points), one row
// each: the job key, the names and the values they stand for, the meaning
// (common/choice_table.hpp). The app derives the schema, the defaults (the member initializers of
// SolverConfig) and the job-to-config mapping from it.
#pragma once

#include "common/choice_table.hpp"
#include "mpm/solver.hpp"

namespace mpm {

inline constexpr common::ChoiceTable<SolverConfig, 12> kSolverChoices{
    "mpm",
    {common::choice<&SolverConfig::shape, kShapeKindNames>(
         "shape_function", "Shape functions: linear (the paper's), uGIMP or quadratic B-spline."),
     common::choice<&SolverConfig::stress_update, kStressUpdateNames>(
         "update", "Stress update: Update Stress First (the paper's) or Modified USL."),
     common::choice<&SolverConfig::damping_mode, kDampingModeNames>(
         "damping_mode",
         "vector: eq. 8 as written (one norm per node); component: per component, as YADE/PFC."),
     common::choice<&SolverConfig::strain_smoothing, kStrainSmoothingNames>(
         "strain_smoothing",
         "cell: every point of a grid cell gets the cell's volume-averaged velocity gradient "
         "before the material update, and the internal forces come from the cell's mean stress "
         "(cures the checkerboard of softening single-cell tests, but also suppresses real "
         "localisation within a cell; docs/design/mpm.md, Strain smoothing). volumetric: only "
         "the volumetric part (B-bar cell by cell): the points of a cell dilate together, each "
         "keeps its own deviatoric rate, the forces take the cell's mean normal stress. none: "
         "off."),
     common::choice<&SolverConfig::free_density, kFreeDensityNames>(
         "free_density",
         "The dilation of a stress-free point (a disconnected material: an RVE without contacts, a "
         "pulled-apart frictional continuum). point: its own velocity gradient's, as every other "
         "point. grid: its own, but not beyond the density of the material around it (the mass "
         "over the volume that the grid's nodes collect from the points near it): a point that "
         "carries no stress has no force to resist a spurious dilation; its compression, "
         "deviatoric rate and spin stay its own (docs/design/mpm.md, Density of stress-free "
         "points)."),
     common::choice<&SolverConfig::formulation, kFormulationNames>(
         "formulation",
         "total_lagrangian: the grid is the reference configuration (needs mpm.move_points = "
         "false): L = Fdot F^-1 and internal forces from sigma F^-T, so that a single-cell sample "
         "holds its confining pressure at any strain instead of p / F_xx (docs/design/mpm.md, "
         "Total Lagrangian formulation). updated_lagrangian: classical MPM."),
     common::choice<&SolverConfig::grid_positions, kPositionUpdateNames>(
         "position_update",
         "point: the points move with their own (FLIP/PIC) velocity (eq. 10, the paper's); grid: "
         "with the end-of-step grid velocity, which the walls hold, so no point crosses a rigid "
         "base (docs/design/mpm.md, Position update)."),
     common::choice<&SolverConfig::wall_impulse_on_points, kWallImpulseNames>(
         "wall_impulse",
         "grid: a wall's correction of the projected start-of-step velocity (the momentum stage "
         "of Bardenhagen's contact) is only the step's kinematics, and a pure-FLIP point keeps a "
         "velocity into a rigid base that never moves it (as before); points: it is an impulse on "
         "the points, seen by their FLIP velocity and the wall's reaction, one contact impulse per "
         "step (docs/design/mpm.md, Frictional boundaries; a frictional no_penetration wall then "
         "holds a block less well). Only walls (friction, contact) have it."),
     common::choice<&SolverConfig::transfer, kTransferNames>(
         "transfer",
         "flip: the FLIP/PIC velocity blend of mpm.flip (the paper's); apic: affine PIC (Jiang et "
         "al. 2015), each point also carries the grid's velocity gradient, so a homogeneous "
         "deformation survives with one point per cell (docs/design/mpm.md, Transfers)."),
     common::flag<&SolverConfig::move_points>(
         "move_points",
         "false: points keep their initial positions (eq. 10 skipped): only for element tests "
         "whose cell is the sample, e.g. the paper's single-cell triaxial (see docs/design/mpm.md, "
         "Fixed points)."),
     common::choice<&SolverConfig::plane_strain_axis, kPlaneStrainAxisNames>(
         "plane_strain",
         "Plane strain: the thickness axis (the grid has 1 cell along it; the velocity along it is "
         "held at zero and the material sees no strain rate through it, docs/design/mpm.md). "
         "Absent: 3D."),
     common::choice<&SolverConfig::regularisation_average, kAverageKindNames>(
         "regularisation.average",
         "How the regularisation's Gaussian average over l is computed. pairs: summed over every "
         "pair of points within 3 l (exact; its cost grows as the points times (3 l / point "
         "spacing)^2 in plane strain). lattice: the points' tensors spread to a lattice of "
         "spacing l / 3, smoothed there axis by axis and read back (the same kernel to a few per "
         "cent; its cost grows as the points; docs/design/mpm.md, Regularisation).")}};

}  // namespace mpm
