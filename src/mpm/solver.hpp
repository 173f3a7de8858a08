// MPM time stepping (Duverger et al. 2022, section 2.1): Update Stress First (the paper) or
// MUSL, NFLIP velocity update (eqs. 9-10) with an optional PIC blend, Cundall damping (eq. 8).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/choice_table.hpp"
#include "common/param_table.hpp"
#include "common/state_io.hpp"
#include "mpm/boundary.hpp"
#include "mpm/energy.hpp"
#include "mpm/energy_guard.hpp"
#include "mpm/formulation.hpp"
#include "mpm/free_density.hpp"
#include "mpm/gradient_regularisation.hpp"
#include "mpm/grid.hpp"
#include "mpm/grid_solve.hpp"
#include "mpm/material_model.hpp"
#include "mpm/material_points.hpp"
#include "mpm/shape_function.hpp"
#include "mpm/strain_smoothing.hpp"
#include "mpm/transfers.hpp"
#include "mpm/xpic.hpp"

namespace mpm {

/// When the stress is updated within a step.
enum class StressUpdate {
  usf,   ///< Update Stress First: L from the start-of-step nodal velocities (the paper)
  musl,  ///< Modified Update Stress Last: L from re-projected end-of-step point velocities
};
/// The job's names (mpm.update).
inline constexpr std::array<common::Named<StressUpdate>, 2> kStressUpdateNames{
    {{"usf", StressUpdate::usf}, {"musl", StressUpdate::musl}}};
/// The job's names of SolverConfig::grid_positions (mpm.position_update).
inline constexpr std::array<common::Named<bool>, 2> kPositionUpdateNames{
    {{"point", false}, {"grid", true}}};
/// The job's names of SolverConfig::wall_impulse_on_points (mpm.wall_impulse).
inline constexpr std::array<common::Named<bool>, 2> kWallImpulseNames{
    {{"grid", false}, {"points", true}}};
/// The job's names of SolverConfig::plane_strain_axis (mpm.plane_strain); -1 (3D) has none.
inline constexpr std::array<common::Named<int>, 3> kPlaneStrainAxisNames{
    {{"x", 0}, {"y", 1}, {"z", 2}}};

/// Plain run configuration (the app maps the job file onto it). Units in each comment. The member
/// initializers of the numeric knobs are the defaults of their job keys too (kSolverConfig).
struct SolverConfig {
  Grid grid;                            ///< background grid [m]
  ShapeKind shape = ShapeKind::linear;  ///< shape function (the paper: linear)
  StressUpdate stress_update = StressUpdate::usf;
  /// FLIP share of the velocity update in [0, 1] [-]: 1 = pure NFLIP (eq. 9, the paper), 0 = PIC.
  /// Unused with Transfer::apic.
  double flip = 1.0;
  /// Relaxation time of the points' velocities towards the grid's [s]: each step takes the PIC
  /// share 1 - exp(-dt / pic_time) (pic_share), so the sub-grid velocity noise decays at a rate
  /// set in time, not per step, and a finer mesh (a shorter step) damps it no more; 0 = off (the
  /// share is then 1 - flip). Needs flip = 1 and Transfer::flip.
  double pic_time = 0.0;
  /// Order m of the extended PIC update (xpic.hpp, Hammerquist & Nairn 2017) that the PIC share
  /// (1 - flip, or pic_time's) takes: 1 = PIC; m > 1 filters the sub-cell noise as PIC does but
  /// keeps a smooth mode that PIC keeps to lambda to 1 - (1 - lambda)^m. Needs a PIC share and
  /// Transfer::flip [-].
  int xpic_order = 1;
  /// flip: the FLIP/PIC blend above (the paper's); apic: affine PIC (transfers.hpp), which keeps
  /// a homogeneous deformation with one point per cell (docs/design/mpm.md, "Transfers").
  Transfer transfer = Transfer::flip;
  /// true: the points move with the end-of-step grid velocity (x_p += dt sum_v S (V_v + dt a_v)),
  /// which walls constrain; false: with their own blended velocity v_p (eq. 10, the paper).
  bool grid_positions = false;
  /// true: a wall's momentum-stage correction of the projected velocity V(t) (Bardenhagen's) is
  /// an impulse on the points: their FLIP increments and the wall's reaction count it, so a
  /// point's velocity into a wall is taken away. false (default, as before): it is only the
  /// kinematics of the step (L, the PIC share), and a pure-FLIP point keeps a velocity into a
  /// rigid base that the base never lets it move with (docs/design/mpm.md, Frictional boundaries).
  bool wall_impulse_on_points = false;
  common::Vec3 gravity = common::Vec3::Zero();  ///< g of eq. 6 [m/s^2]; zero = no gravity
  double damping = 0.0;                         ///< D of eq. 8, in [0, 1) [-]
  DampingMode damping_mode = DampingMode::cundall_vector;
  double dt = 0.0;   ///< fixed time step [s]; 0 = use cfl
  double cfl = 0.5;  ///< CFL number in (0, 1] when dt == 0 [-]
  /// Nodes with m_v < mass_threshold * (mean active nodal mass) get zero velocity and
  /// acceleration [-]; in (0, 1).
  double mass_threshold = 1e-6;
  /// false: eq. 10 is skipped, the points keep their initial positions (their integration
  /// weights stay those of the regular arrangement) while F, volume, stress and velocity evolve.
  /// Only for element tests whose cell IS the sample (the paper's single-cell triaxial): the
  /// material does not advect. docs/design/mpm.md, "Fixed points".
  bool move_points = true;
  /// A fixed dt above the stability limit h_min / (c + |v|_max) (c: the materials' largest wave
  /// speed) is refused: common::NumericalError naming the step, time and both steps. false only
  /// for tests that provoke a blow-up on purpose.
  bool refuse_unstable_dt = true;
  /// Blow-up guard: a point whose volume leaves [V0 / ratio, V0 * ratio] stops the run
  /// (common::NumericalError naming the step, time, point id and the ratio) [-]; > 1. A point
  /// without stress, or whose material is dilute (MaterialModel::mark_dilute), may expand beyond.
  double max_volume_ratio = 10.0;
  /// Plane strain (docs/design/mpm.md, "Plane strain"): the thickness axis 0, 1 or 2 (-1: 3D). The
  /// grid must have exactly one cell along it; the nodal velocity along it is held at zero and the
  /// thickness row and column of each point's L are zeroed before the material sees it.
  int plane_strain_axis = -1;
  /// Quasi-static mass scaling s >= 1 [-] (docs/design/mpm.md, "Mass scaling"): nodal masses and
  /// momenta (the inertia) are s times the points' masses, gravity acts on the real mass; the CFL
  /// step grows by sqrt(s). 1: off.
  double mass_scaling = 1.0;
  /// Kinetic energy over internal work above which a mass-scaled run is warned that it is no
  /// longer quasi-static [-] (mpm/energy.hpp, QuasiStaticWatch).
  double quasi_static_ratio = 0.01;
  /// cell: every point of a grid cell gets the cell's volume-averaged L before the material
  /// update, and the internal forces use the cell's volume-averaged stress, in USF and MUSL
  /// (docs/design/mpm.md, "Strain smoothing"). none: each point its own L and stress.
  StrainSmoothing strain_smoothing = StrainSmoothing::none;
  /// grid: a stress-free point does not dilate beyond the density of the material around it
  /// (mpm/free_density.hpp; docs/design/mpm.md, "Density of stress-free points"). point: its own
  /// L's dilation, as every other point.
  FreeDensity free_density = FreeDensity::point;
  /// total_lagrangian: the grid is the reference configuration (only with move_points = false):
  /// L = Fdot F^-1 and the internal forces use sigma F^-T, so that a single-cell sample holds
  /// its confining pressure at any strain (docs/design/mpm.md, "Total Lagrangian formulation").
  Formulation formulation = Formulation::updated_lagrangian;
  /// Nonlocal strain-gradient regularisation (mpm/gradient_regularisation.hpp, docs/design/mpm.md
  /// "Regularisation"): l > 0 and H > 0 together, or both 0 (off). The material length l [m].
  double regularisation_length = 0.0;
  /// Its modulus H [Pa]: the stiffness of the energy on a point's strain minus its average.
  double regularisation_modulus = 0.0;
  /// How the regularisation's Gaussian average is computed: lattice (through a lattice of
  /// spacing l / 3, cost ~ points + lattice nodes) or pairs (exact, cost ~ points x neighbours
  /// within 3 l; docs/design/mpm.md, "Regularisation").
  AverageKind regularisation_average = AverageKind::lattice;
  /// Sub-cell stress relaxation (mpm/subcell_relaxation.hpp; docs/design/mpm.md): the points of
  /// a cell relax their stresses towards the cell's mean over tau = subcell_relaxation h / c (h
  /// the smallest grid spacing, c the materials' largest wave speed, mass-scaled); 0 = off [-].
  double subcell_relaxation = 0.0;
  /// Energy-growth guard (mpm/energy_guard.hpp): the share of the scene's energy scale that the
  /// energy created by the steps may exceed, 10 steps in a row with a growing kinetic energy,
  /// before the run stops (common::NumericalError) [-]; 0 = off.
  double energy_guard = 0.5;
  /// Throws common::InputError naming the job key (kSolverConfig), its value and the rule.
  void validate() const;
};

/// [mpm]: the numeric knobs of SolverConfig (the grid, shape, stress update, damping mode,
/// gravity and move_points are mapped by the app: they are not numbers with a range).
inline constexpr auto kSolverConfig = common::make_table<SolverConfig>(
    "mpm::SolverConfig", "mpm",
    {{"flip", &SolverConfig::flip, common::Unit::Dimensionless, common::in_cc(0, 1),
      common::Source::job_default,
      "FLIP fraction of the PIC/FLIP velocity blend; 1 is the paper's NFLIP."},
     {"pic_time", &SolverConfig::pic_time, common::Unit::Time, common::ge(0),
      common::Source::job_default,
      "Relaxation time of the points' velocities towards the grid's: each step blends in the PIC "
      "share 1 - exp(-dt / pic_time), a filter of the transfer's noise set in time, the same on "
      "any mesh (mpm.flip per step is not); needs flip = 1; 0 = off (docs/design/mpm.md, "
      "Transfers)."},
     {"xpic_order", &SolverConfig::xpic_order, common::Unit::Dimensionless, common::in_cc(1, 8),
      common::Source::job_default,
      "Order m of the extended PIC update (XPIC(m), Hammerquist & Nairn 2017) that the PIC share "
      "(1 - flip, or pic_time's) takes: 1 = PIC; m > 1 removes the sub-cell velocity noise as PIC "
      "does but damps the grid's resolved motion far less (a mode PIC keeps to lambda is kept to "
      "1 - (1 - lambda)^m), for m - 1 extra point-grid round trips per step. Needs flip < 1 or "
      "pic_time > 0 (flip = 0: XPIC alone) (docs/design/mpm.md, Transfers)."},
     {"damping", &SolverConfig::damping, common::Unit::Dimensionless, common::in_co(0, 1),
      common::Source::job_default, "Cundall damping D of the nodal accelerations (eq. 8)."},
     {"dt", &SolverConfig::dt, common::Unit::Time, common::ge(0), common::Source::job_optional,
      "Fixed MPM time step; absent or 0: from the CFL condition."},
     {"cfl", &SolverConfig::cfl, common::Unit::Dimensionless, common::in_oc(0, 1),
      common::Source::job_default, "CFL number when dt is not given."},
     {"mass_threshold", &SolverConfig::mass_threshold, common::Unit::Dimensionless,
      common::in_oo(0, 1), common::Source::job_default,
      "Nodes lighter than this fraction of the typical nodal mass are inactive."},
     {"max_volume_ratio", &SolverConfig::max_volume_ratio, common::Unit::Dimensionless,
      common::gt(1), common::Source::cpp_only,
      "Blow-up guard: a point whose volume leaves [V0 / ratio, V0 * ratio] stops the run; a "
      "stress-free point (a disconnected material, a spray of grains) may grow beyond V0 * "
      "ratio, since its volume carries no force."},
     {"mass_scaling", &SolverConfig::mass_scaling, common::Unit::Dimensionless,
      common::in_cc(1, 1e6), common::Source::job_default,
      "Quasi-static mass scaling: the inertia (not the weight) is multiplied by it, the time step "
      "by its square root (at most 1000 times); 1 = off (docs/design/mpm.md, Mass scaling)."},
     {"quasi_static_ratio", &SolverConfig::quasi_static_ratio, common::Unit::Dimensionless,
      common::gt(0), common::Source::job_default,
      "With mass_scaling > 1: the log warns once when the kinetic energy exceeds this fraction "
      "of the internal work."},
     {"subcell_relaxation", &SolverConfig::subcell_relaxation, common::Unit::Dimensionless,
      common::ge(0), common::Source::job_default,
      "Sub-cell stress relaxation: each point's strain rate gets -(sigma_p - sigma_cell) / (rho "
      "c^2 tau), so that the points of a grid cell approach their cell's mean stress over tau = "
      "subcell_relaxation h / c (h the smallest spacing, c the largest wave speed): a pattern in "
      "the null space of the points-to-grid map (one point of a cell loaded, its neighbours "
      "floating) relaxes instead of persisting. The cell's deformation rate is unchanged; 0 = off "
      "(docs/design/mpm.md, Sub-cell stress relaxation)."},
     {"regularisation.length", &SolverConfig::regularisation_length, common::Unit::Length,
      common::ge(0), common::Source::job_default,
      "Material length l of the nonlocal strain-gradient regularisation: an elastic energy on "
      "each point's strain minus its Gaussian average (standard deviation l, cut at 3 l) over "
      "its material, which sets a shear band's thickness instead of the cell; 0 = off "
      "(docs/design/mpm.md, Regularisation)."},
     {"regularisation.modulus", &SolverConfig::regularisation_modulus, common::Unit::Pressure,
      common::ge(0), common::Source::job_default,
      "Modulus H of that energy, given with the length: of the order of the material's shear "
      "modulus (docs/design/mpm.md, Regularisation); 0 = off."},
     {"energy_guard", &SolverConfig::energy_guard, common::Unit::Dimensionless, common::ge(0),
      common::Source::job_default,
      "Energy-growth guard: the run stops (exit 3, naming the step, the time and the fastest "
      "point) when the energy its steps create (kinetic energy + internal work - the work of "
      "gravity, loads, walls and damping since the start) exceeds this share of the scene's "
      "energy scale 10 steps in a row while the kinetic energy grows: a time step above the "
      "stability limit, an unstable material update. 0 = off, for a scene that injects energy "
      "the balance does not see (docs/design/mpm.md, Energy-growth guard)."}});

/// Owns the points and the grid fields; materials are not owned and must outlive the solver.
class Solver {
 public:
  /// materials[k] serves the points with material == k. Throws common::InputError on a bad
  /// configuration, bad points, or a point whose material index has no model.
  Solver(SolverConfig config, MaterialPoints points, std::vector<MaterialModel*> materials);

  /// Velocity constraint on a node set (resolved once, here). An empty name becomes
  /// "constraint_<k>", k its index in add_constraint order; names must be unique (InputError).
  void add_constraint(const VelocityConstraint& constraint);
  /// Pressure/traction on a face of the material (recomputed every step from the current area).
  /// The face's facets are the points on that face of the material NOW (call before stepping);
  /// they are saved with the state.
  void add_traction(const TractionLoad& load);

  /// Advances one step. Throws common::NumericalError (step, time, point id, value) when a point
  /// leaves the grid, or a volume becomes non-positive or NaN, or a stress non-finite.
  void step();
  /// n steps.
  void run(std::int64_t n);

  /// Time step the next step() will use [s] (fixed, or CFL from the materials' wave speeds).
  [[nodiscard]] double next_dt() const;

  [[nodiscard]] const MaterialPoints& points() const { return points_; }
  /// Mutable access, e.g. to set initial velocities or stresses before the first step.
  [[nodiscard]] MaterialPoints& points() {
    kinetic_step_ = -1;  // the points may change: no cached kinetic energy
    return points_;
  }
  [[nodiscard]] const GridFields& grid_fields() const { return fields_; }
  [[nodiscard]] const SolverConfig& config() const { return config_; }
  [[nodiscard]] double time() const { return time_; }  ///< [s]
  [[nodiscard]] std::int64_t step_count() const { return step_; }
  /// Kinetic energy (with the scaled inertia) and internal work since the start (mpm/energy.hpp).
  [[nodiscard]] Energies energies() const;
  /// Loaded area of each traction load in the last step [m^2], in add_traction order.
  [[nodiscard]] const std::vector<double>& traction_areas() const { return traction_areas_; }
  /// Force each constraint exerted ON the material in the last step [N], in add_constraint order:
  /// sum over its nodes of m_i (a_i after it - a_i before it) (zero while inactive;
  /// docs/design/mpm.md, "Frictional boundaries and reactions").
  [[nodiscard]] const std::vector<common::Vec3>& reactions() const { return reactions_; }
  /// Displacement of each constraint [m]: the integral of its prescribed velocity over the time
  /// it was active (prescribed_velocity; trapezoidal per step).
  [[nodiscard]] const std::vector<common::Vec3>& constraint_displacements() const {
    return displacements_;
  }
  /// Names of the constraints, in add_constraint order.
  [[nodiscard]] std::vector<std::string> constraint_names() const;

  /// Writes the MPM state as named fields (docs/design/mpm.md, "Checkpoint"): solver/step,
  /// solver/time, solver/internal_work, points/id, points/x, points/v, points/mass, points/volume,
  /// points/volume0, points/half_width0, points/stress, points/F, points/L, points/material,
  /// points/C (APIC), points/regularisation_strain (with the regularisation, after a step),
  /// loads/traction_<k>/point_slots. The materials'
  /// own state is written by their owner (e.g. LinearElastic::save).
  void save(common::StateWriter& writer) const;
  /// Restores what save wrote; a run continued from it is bit-for-bit the uninterrupted one.
  /// Throws common::InputError on a missing field or inconsistent sizes. A checkpoint without
  /// solver/internal_work (written before it existed) restarts the internal work from 0.
  void load(const common::StateReader& reader);

 private:
  void prepare_grid(std::int64_t step, double t);
  // The two stages of a step, written once; USF runs stress then momentum, MUSL momentum, the
  // re-projection, then stress.
  /// L of the points from the nodal velocities, their stress, the blow-up checks at t + dt.
  void stress_stage(double t, double dt);
  /// Forces, accelerations, the walls and constraints on them, then G2P (velocities, positions).
  void momentum_stage(double t, double dt);
  /// MUSL: the points' new momentum to the nodes with the start-of-step weights, constrained at
  /// t + dt.
  void reproject_momentum(double t, double dt);
  void update_stress(double dt);
  void update_material_stress(double dt);
  /// G2P of the point velocities (and positions, C_p): FLIP/PIC or APIC by config_.transfer.
  void update_points(double dt);
  void add_external_loads();
  /// P2G of the internal forces; with strain smoothing from the cell-averaged stresses; with the
  /// regularisation, its stress added first.
  void internal_force();
  void check_points(double t_end) const;
  void advance_displacements(double t, double dt);
  /// The stable step h_min / (c + |v|_max) [s] and the speed used [m/s].
  [[nodiscard]] double stable_dt(double& speed) const;
  /// Plane strain: holds the thickness component of the nodal velocity / acceleration.
  void hold_thickness_velocity();
  void hold_thickness_acceleration();
  /// With wall_impulse_on_points: a -= wall_dv / dt before the constraints on the acceleration
  /// (the walls' trial velocity is then the projected one plus a dt).
  void project_wall_trial(double dt);
  /// Mass scaling: multiplies the nodal momenta (and masses when `with_mass`) by s.
  void scale_inertia(bool with_mass);
  /// Energy guard: the grid's kinetic energy 1/2 sum m_v |V_v|^2 over the active nodes [J].
  [[nodiscard]] double grid_kinetic_energy() const;
  /// Energy guard: internal_force() with the internal part of the nodal forces kept apart.
  void internal_force_tracked();
  /// Energy guard: the step's work of every nodal force but the internal one, from the final
  /// accelerations: dt sum (m_v a_v - f_int,v) . V_v, V_v the velocity the materials' L is
  /// taken from (V(t) in USF, V(t) + a dt in MUSL) [J].
  [[nodiscard]] double grid_external_work(double dt) const;
  /// Energy guard: observe the step; throws common::NumericalError when it trips.
  void observe_energy(double t_end);

  SolverConfig config_;
  MaterialPoints points_;
  std::vector<MaterialModel*> materials_;
  std::vector<ResolvedConstraint> constraints_;
  std::vector<common::Vec3> reactions_;      ///< [N], per constraint, last step
  std::vector<common::Vec3> displacements_;  ///< [m], per constraint
  std::vector<TractionLoad> tractions_;
  std::vector<std::vector<std::int64_t>> traction_points_;  ///< facet point slots per load
  std::vector<double> traction_areas_;
  GridFields fields_;
  StencilCache cache_;
  PointBins bins_;
  double threshold_ = 0.0;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  double internal_work_ = 0.0;  ///< sum over steps of the stress power times dt [J]
  // Per-material gather buffers (used when there is more than one material).
  std::vector<std::int64_t> gather_ids_;
  std::vector<common::Mat3> gather_L_;
  std::vector<common::Mat3> gather_stress_;
  std::vector<std::uint8_t> gather_dilute_;
  /// By slot, from the last stress update: the point's material is dilute
  /// (MaterialModel::mark_dilute), exempt from the upper volume bound of check_points.
  std::vector<std::uint8_t> dilute_;
  std::vector<std::pair<std::int64_t, std::int64_t>> smoothing_scratch_;  ///< (cell, point)
  XpicScratch xpic_scratch_;                 ///< xpic_velocity's work arrays
  std::vector<common::Vec3> xpic_velocity_;  ///< V* of XPIC(m) on the grid [m/s]
  std::vector<double> density_node_m_, density_node_v_, density_rho_;  ///< FreeDensity::grid
  std::vector<common::Mat3> force_stress_;                ///< the stress the internal forces use
  std::optional<GradientRegularisation> regularisation_;  ///< with regularisation_length > 0
  EnergyGuard guard_{0.0};                ///< energy-growth guard (config_.energy_guard)
  std::vector<common::Vec3> f_internal_;  ///< guard: f_int by node, this step [N]
  double w_ext_step_ = 0.0;               ///< guard: the step's external work so far [J]
  std::int64_t kinetic_step_ = -1;        ///< the step whose kinetic energy the guard summed
  double kinetic_ = 0.0;                  ///< that kinetic energy [J]

 public:
  /// The energy guard's state (its balance and the largest share seen, for the log).
  [[nodiscard]] const EnergyGuard& energy_guard() const { return guard_; }
};

}  // namespace mpm
