// Job-file sections of the MPM (paper section 2.1): [mpm], [mpm.grid], [[mpm.body]], [mpm.elastic],
// [[mpm.velocity]], [[mpm.traction]]. The numeric knobs of [mpm] are the rows of mpm's parameter
// table (mpm/solver.hpp, kSolverConfig), the keys of [mpm.elastic] those of farm::kElasticMaterial
// (farm/elastic_material.hpp).
#include "app/job/schema.hpp"
#include "app/job/schema_params.hpp"
#include "app/setup/mpm_setup.hpp"
#include "farm/elastic_material.hpp"
#include "mpm/boundary.hpp"
#include "mpm/friction.hpp"
#include "mpm/solver.hpp"
#include "mpm/solver_choices.hpp"

namespace app {

namespace {

// [mpm]: the scheme, its knobs and gravity; [mpm.regularisation].
void add_scheme(Schema& s) {
  using Q = Quantity;
  s.add("mpm", Type::Table, "The material point method at the scale of the structure (`run`).");
  add_choices(s, mpm::kSolverChoices);  // shape_function, update, ..., move_points, plane_strain
  add_params(s, mpm::kSolverConfig);    // flip, damping, dt, cfl, mass_threshold, mass_scaling, ...
  s.add("mpm.end_time", Type::Float, "Simulated time at which the run ends.")
      .unit(Q::Time)
      .in(0, std::nullopt, true)
      .need();
  s.add("mpm.gravity", Type::FloatList, "Gravity vector; absent: no gravity.")
      .unit(Q::Acceleration)
      .len(3, 3);
  s.add("mpm.regularisation", Type::Table,
        "Nonlocal strain-gradient regularisation of a softening material: length and modulus "
        "together; absent: none (docs/design/mpm.md, Regularisation).");
  add_params(s, mpm::kSolverConfig, "regularisation");
  add_choices(s, mpm::kSolverChoices, "regularisation");  // average
}

// [mpm.grid] and the [[mpm.body]] boxes of material points.
void add_grid_and_bodies(Schema& s) {
  using Q = Quantity;
  s.add("mpm.grid", Type::Table, "Structured grid of hexahedral cells.").need();
  s.add("mpm.grid.origin", Type::FloatList, "Corner of the grid with the smallest coordinates.")
      .unit(Q::Length)
      .len(3, 3)
      .need();
  s.add("mpm.grid.spacing", Type::FloatList, "Cell size along x, y, z.")
      .unit(Q::Length)
      .in(0, std::nullopt, true)
      .len(3, 3)
      .need();
  s.add("mpm.grid.cells", Type::IntList, "Number of cells along x, y, z.")
      .in(1, std::nullopt)
      .len(3, 3)
      .need();

  s.add("mpm.body[]", Type::TableList,
        "A box of material points, regularly spaced in each cell it covers.")
      .need();
  s.add("mpm.body[].min", Type::FloatList, "Lower corner of the box.")
      .unit(Q::Length)
      .len(3, 3)
      .need();
  s.add("mpm.body[].max", Type::FloatList, "Upper corner of the box.")
      .unit(Q::Length)
      .len(3, 3)
      .need();
  s.add("mpm.body[].points_per_cell", Type::Int,
        "Material points per cell along each axis, at the regular positions (k + 1/2) / n of the "
        "cell: one count for every axis, or one per axis (e.g. [2, 1, 2] for plane strain).")
      .in(1, 8)
      .or_per_axis()
      .need();
  s.add("mpm.body[].density", Type::Float, "Bulk density of the material (mass per unit volume).")
      .unit(Q::Density)
      .in(0, std::nullopt, true)
      .need();
  s.add("mpm.body[].material", Type::String,
        "Material of the points: a DEM RVE each, or the continuum of [mpm.elastic] (linear "
        "elastic, or Drucker-Prager with a friction angle).")
      .one_of(kBodyMaterialNames)
      .need();
  s.add("mpm.body[].initial_stress", Type::FloatList,
        "Initial Cauchy stress xx, yy, zz, yz, xz, xy (tension positive); dem: from the RVEs.")
      .unit(Q::Pressure)
      .len(6, 6);
}

// [mpm.elastic]: the continuum material of the bodies that are not DEM (farm::kElasticMaterial).
void add_elastic(Schema& s) {
  s.add(
      "mpm.elastic", Type::Table,
      "Continuum material for bodies with material = \"elastic\": linear elastic "
      "(verification), or with friction_angle a frictional continuum (a reference for the RVEs).");
  add_params(s, farm::kElasticMaterial);  // young_modulus, poisson_ratio, the angles, softening
}

// The boundary conditions: [[mpm.velocity]] constraints and [[mpm.traction]] loads.
void add_boundaries(Schema& s) {
  using Q = Quantity;
  s.add("mpm.velocity[]", Type::TableList,
        "Imposed velocity components on grid nodes: a grid face, one node, or the nodes in a box.");
  s.add("mpm.velocity[].face", Type::String, "Grid face (give one of face, node, min and max).")
      .one_of(mpm::kFaceNames);
  s.add("mpm.velocity[].node", Type::FloatList,
        "Position of one grid node, e.g. to pin rigid motions (docs/design/mpm.md).")
      .unit(Q::Length);
  s.add("mpm.velocity[].min", Type::FloatList,
        "Lower corner of a box: every node inside it, boundary included (e.g. a padded grid's "
        "platen).")
      .unit(Q::Length);
  s.add("mpm.velocity[].max", Type::FloatList, "Upper corner of the box of min.").unit(Q::Length);
  s.add("mpm.velocity[].x", Type::Float, "Imposed x velocity; absent: free.").unit(Q::Velocity);
  s.add("mpm.velocity[].y", Type::Float, "Imposed y velocity; absent: free.").unit(Q::Velocity);
  s.add("mpm.velocity[].z", Type::Float, "Imposed z velocity; absent: free.").unit(Q::Velocity);
  s.add("mpm.velocity[].friction", Type::Float,
        "Coulomb friction coefficient: the nodes form a rigid wall moving at (x, y, z) (absent "
        "components 0; the normal one must be given), tangential slip resisted up to friction "
        "times the normal force (0: smooth, large: rough). docs/design/mpm.md, Frictional "
        "boundaries.")
      .in(0, std::nullopt);
  s.add("mpm.velocity[].normal", Type::String,
        "Side of the material a frictional box or node wall lies on (a face gives its own).")
      .one_of(mpm::kFaceNames);
  s.add("mpm.velocity[].contact", Type::String,
        "Normal behaviour of a frictional wall: fixed (normal velocity imposed) or "
        "no_penetration (the material may leave the wall); absent: fixed.")
      .one_of(mpm::kWallContactNames);
  s.add("mpm.velocity[].from", Type::Float, "Time from which the constraint acts; absent: 0.")
      .unit(Q::Time)
      .in(0, std::nullopt);
  s.add("mpm.velocity[].until", Type::Float,
        "Time from which the constraint stops acting (e.g. a gate removed); absent: never.")
      .unit(Q::Time)
      .in(0, std::nullopt, true);
  s.add("mpm.velocity[].name", Type::String,
        "Name of the constraint in reactions.csv and results.h5 (letters, digits, _ and -); "
        "absent: velocity_<index>.");

  s.add("mpm.traction[]", Type::TableList,
        "A pressure on a face of the material, applied on its current area.");
  s.add("mpm.traction[].face", Type::String, "Face of the material.")
      .one_of(mpm::kFaceNames)
      .need();
  s.add("mpm.traction[].pressure", Type::Float, "Pressure (compression positive) on the face.")
      .unit(Q::Pressure)
      .in(0, std::nullopt)
      .need();
}

}  // namespace

void add_mpm_sections(Schema& s) {
  add_scheme(s);
  add_grid_and_bodies(s);
  add_elastic(s);
  add_boundaries(s);
}

}  // namespace app
