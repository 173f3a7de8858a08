// Analytic verification set-ups of the MPM module, shared by the tests (which assert) and
// study_mpm (which prints refinement and sensitivity tables). Not used by production runs.
#pragma once

#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "mpm/formulation.hpp"
#include "mpm/shape_function.hpp"
#include "mpm/solver.hpp"

namespace mpm {

/// 1D elastic bar, first mode (Sulsky/Bardenhagen): length 25 m, E = 100 Pa, rho = 1 kg/m^3,
/// nu = 0, fixed at x = 0, free at x = 25, v(X, 0) = 0.1 sin(pi X / 50) m/s; transverse
/// velocities constrained to zero. Analytic period 4 L / c = 10 s.
struct BarResult {
  double period = 0.0;            ///< measured from the centre-of-mass velocity zero crossings [s]
  double period_analytic = 10.0;  ///< [s]
  double energy_initial = 0.0;    ///< [J]
  double energy_drift = 0.0;      ///< max over the run of |E(t) - E(0)| / E(0) [-]
  std::int64_t steps = 0;
};
BarResult run_elastic_bar(ShapeKind shape, int cells = 25, double periods = 2.0, double cfl = 0.1,
                          StressUpdate scheme = StressUpdate::usf, double pic_fraction = 0.0);

/// Elastic column of height H = 1 m under its own weight (rho = 1000 kg/m^3, g = 10 m/s^2 along
/// -z, E = 1e7 Pa, nu = 0), lateral velocities constrained, bottom fixed, brought to rest with
/// Cundall damping. Exact: sigma_zz(Z) = -rho g (H - Z) (Z: initial height of the point).
struct ColumnResult {
  int cells = 0;               ///< cells over the height
  double rms_error = 0.0;      ///< RMS over points of |sigma_zz - exact| / (rho g H) [-]
  double max_error = 0.0;      ///< max over points of the same [-]
  double kinetic_ratio = 0.0;  ///< final kinetic energy / potential energy scale (rest check)
  std::int64_t steps = 0;
};
/// Variants of the column: a soft one (young_modulus = rho g H / 0.2 compresses its base by a
/// log strain of 0.2, so the points cross cell faces: the "compacting column" of Steffen, Kirby
/// and Berzins 2008; the exact point stress stays -rho g (H - Z), the weight above the point),
/// and plane strain (a one-cell-thick grid along y, SolverConfig::plane_strain_axis = 1, 2 x 1 x 2
/// points per cell). Both keep the defaults of the column above when not set.
struct ColumnOptions {
  double young_modulus = 1e7;  ///< [Pa]
  bool plane_strain = false;
};
ColumnResult run_self_weight_column(ShapeKind shape, int cells, double transits = 60.0,
                                    const ColumnOptions& options = {});

/// The paper's single-cell triaxial test (section 3): one 1 m cell, 8 points at (1/4, 3/4),
/// confining pressure on the x and y faces as TractionLoads, bottom nodes fixed in z, top nodes
/// moving down at V = -I_n sqrt(p / rho) (eq. 13), points initially at rest, linear elastic
/// material starting from -p I. For uGIMP and B-splines the grid gets one extra cell on each
/// side; the constraints then hold every node plane at or below z = 0 / at or above z = 1.
struct TriaxialConfig {
  ShapeKind shape = ShapeKind::linear;
  double youngs_modulus = 50e6;     ///< [Pa]
  double poisson_ratio = 0.25;      ///< [-]
  double density = 1600.0;          ///< [kg/m^3]
  double pressure = 100e3;          ///< confining pressure p [Pa]
  double inertial_number = 2.5e-4;  ///< I_n of eq. 13 [-]
  double axial_strain = 0.03;       ///< compressive axial strain to reach [-]
  double damping = 0.2;             ///< D of eq. 8 [-]
  double cfl = 0.5;                 ///< [-]
  /// Offsets of the 8 points from their regular positions [m] (empty: none), in fill_box order
  /// (x fastest, then y, then z).
  std::vector<common::Vec3> offsets;
  /// Added to the initial stress -p I (e.g. a small shear, as DEM RVEs carry) [Pa].
  common::Mat3 initial_stress_seed = common::Mat3::Zero();
  bool move_points = true;  ///< SolverConfig::move_points
  /// SolverConfig::formulation (total_lagrangian needs move_points = false).
  Formulation formulation = Formulation::updated_lagrangian;
  /// Also constrain the rigid motions in the horizontal plane (3-2-1 support on the bottom
  /// nodes (0,0,0) in x, y and (1,0,0) in y); the paper's set-up leaves them free.
  bool pin_rigid_modes = false;
  int points_per_cell = 2;             ///< per axis: 2 is the paper's 8 points
  Transfer transfer = Transfer::flip;  ///< SolverConfig::transfer
};
struct TriaxialResult {
  double lateral_error = 0.0;      ///< max over points and steps of |sigma_xx or yy / (-p) - 1|
  double lateral_error_end = 0.0;  ///< the same at the end only
  double axial_error = 0.0;        ///< max |sigma_zz - (-p + E eps)| / (E eps) at the end [-]
  double axial_strain = 0.0;       ///< eps = sum dt mean(L_zz) reached (negative) [-]
  double mean_lateral = 0.0;       ///< mean sigma_xx, sigma_yy at the end [Pa]
  double mean_axial = 0.0;         ///< mean sigma_zz at the end [Pa]
  std::int64_t steps = 0;
  double max_displacement = 0.0;  ///< largest distance of a point from its start at the end [m]
};
TriaxialResult run_single_cell_triaxial(const TriaxialConfig& config);

}  // namespace mpm
