// dem::Rve: the façade the MPM farm drives. One step = the continuum velocity gradient L over the
// MPM step dt, applied to the periodic cell over the quasi-static time T_p of Duverger et al.
// 2022 (eqs. 11-12), or over dt itself where the material flows faster than that (RveRate);
// an RVE without contacts is a disconnected, stress-free material (ContactLoss). Returns the
// Love-Weber Cauchy stress, TENSION POSITIVE (the seam convention).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "common/choice_table.hpp"
#include "common/state_io.hpp"
#include "common/types.hpp"
#include "dem/packing_io.hpp"
#include "dem/params.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// How fast an RVE is sheared (job key dem.coupling.rate; docs/design/rve_step.md).
enum class RveRate : std::uint8_t {
  /// Always over T_p of eq. (11), at the coupling inertial number I_n, however fast the material
  /// flows (the paper; results of before the key).
  coupling,
  /// Over min(T_p, dt): the RVE's inertial number is max(I_n, I of the material), so a flow
  /// keeps its own rate (mu(I)) and a slow material stays quasi-static at I_n.
  material,
};

/// What an RVE that has lost every contact does with a dilation (job key
/// dem.coupling.contact_loss; docs/design/rve_step.md).
enum class ContactLoss : std::uint8_t {
  /// The cell follows every increment (results of before the key): a stress-free point strained
  /// by its neighbours' nodes stretches its cell without bound.
  strained,
  /// A disconnected, stress-free material (Dunatunga & Kamrin 2015) once the RVE has no contact
  /// and its solid fraction is below disconnect_fraction: the dilation goes to a free volume
  /// outside the cell, which is held; a compression closes the free volume first, then strains
  /// the cell again from the state in which it was held. Above that fraction a contact-free RVE
  /// is a dense gas and follows every increment.
  disconnected,
};

/// The job's names (dem.coupling.rate, dem.coupling.contact_loss, dem.coupling.end_forces).
inline constexpr std::array<common::Named<RveRate>, 2> kRveRateNames{
    {{"material", RveRate::material}, {"coupling", RveRate::coupling}}};
inline constexpr std::array<common::Named<ContactLoss>, 2> kContactLossNames{
    {{"disconnected", ContactLoss::disconnected}, {"strained", ContactLoss::strained}}};
inline constexpr std::array<common::Named<bool>, 2> kEndForcesNames{
    {{"separate", false}, {"carried", true}}};
inline constexpr std::array<common::Named<bool>, 2> kFreeFlightNames{
    {{"stepped", false}, {"one_step", true}}};

/// Parameters of an RVE: material, numerics and the quasi-static step control. The member
/// initializers are the defaults of the job keys too (kRveParams).
struct RveParams {
  Material material;
  Numerics numerics;
  double inertial_number = 2.5e-4;    ///< I of eq. (11) [-], > 0
  double d50 = 0.0;                   ///< d50 of eq. (11) [m]; 0: mass median of the spheres
  double p_floor = 1e3;               ///< floor on p in eq. (11) [Pa], > 0
  double max_strain_per_step = 1e-5;  ///< bound on max|L dt_DEM| per DEM step [-]
  std::int64_t max_steps_per_call = 2'000'000;  ///< cap on DEM steps per step() [-]
  double initial_pressure = 0.0;  ///< > 0: equilibrate isotropically at construction [Pa]
  /// DEM steps between computations of the critical time step in step(); 1: every step() [-]
  std::int64_t dt_refresh = 1;
  /// The forces of the end state carried to the next step() (job key dem.coupling.end_forces =
  /// "carried"): computed with the step's dt and L, they give its stress and drive the next
  /// step's first DEM step, one force evaluation fewer per step(). false ("separate"): a
  /// zero-length evaluation gives the stress, the next step() computes the forces again.
  bool carry_end_forces = true;
  /// ContactLoss::disconnected: the solid fraction below which a contact-free RVE is a
  /// disconnected material (job key dem.coupling.disconnect_fraction) [-], in (0, 1)
  double disconnect_fraction = 0.5;
  /// The fewest DEM steps of an RVE step (job key dem.coupling.min_dem_steps) [-], >= 1: a small
  /// increment runs over at least this many DEM steps, so that the RVE relaxes between MPM steps
  std::int64_t min_dem_steps = 1;
  RveRate rate = RveRate::material;                      ///< job key dem.coupling.rate
  ContactLoss contact_loss = ContactLoss::disconnected;  ///< job key dem.coupling.contact_loss
  /// An RVE step without contacts in which no pair can touch runs as one DEM step of the whole
  /// T_p (job key dem.coupling.free_flight = "one_step"; free_flight.hpp); false: n steps.
  bool free_flight = false;

  /// Throws common::InputError naming the job key of the first invalid entry (kMaterial,
  /// kNumerics, kRveParams).
  void validate() const;
};

/// [dem.coupling] and the C++-only step controls of RveParams (material and numerics: kMaterial,
/// kNumerics).
inline constexpr auto kRveParams = common::make_table<RveParams>(
    "dem::RveParams", "dem.coupling",
    {{"inertial_number", &RveParams::inertial_number, Unit::Dimensionless, common::in_co(1e-6, 1),
      Source::job_required,
      "Inertial number I_n of the quasi-static time T_p (eq. 11). At least 1e-6: the DEM steps "
      "per increment grow as 1 / I_n, and below I ~ 1e-3 the response is already "
      "quasi-static."},
     {"max_strain_per_step", &RveParams::max_strain_per_step, Unit::Dimensionless,
      common::in_co(1e-8, 1), Source::job_default,
      "Guard: largest strain increment of one DEM step (more DEM steps than T_p / dt_DEM when "
      "needed). At least 1e-8: an MPM strain increment of 1e-4 is then 10^4 DEM steps; 1e-300 "
      "made every RVE step run its cap of 2,000,000 DEM steps."},
     {"pressure_floor", &RveParams::p_floor, Unit::Pressure, common::gt(0), Source::job_default,
      "Guard: smallest pressure used in T_p (an RVE losing its contacts)."},
     {"d50", &RveParams::d50, Unit::Length, common::ge(0), Source::cpp_only,
      "d50 of eq. (11); 0: the mass median of the spheres."},
     {"disconnect_fraction", &RveParams::disconnect_fraction, Unit::Dimensionless,
      common::in_oo(0, 1), Source::job_default,
      "With contact_loss = \"disconnected\": the solid fraction below which an RVE without "
      "contacts is a disconnected material (stress-free, held; docs/design/rve_step.md). Above "
      "it a contact-free RVE is a dense granular gas: it follows every increment, and a shear "
      "or a compression makes contacts again."},
     {"dt_refresh", &RveParams::dt_refresh, Unit::Dimensionless, common::ge(1), Source::job_default,
      "DEM steps between computations of an RVE's critical time step: an RVE step computes it "
      "anew once this many DEM steps have run since the last computation, or when the RVE has "
      "more than 5 % more contacts than then (its stiffness grew). 1: at every RVE step. Larger "
      "values save the computation (half a DEM step) in RVE steps of one or two DEM steps, as "
      "YADE's GlobalStiffnessTimeStepper.timeStepUpdateInterval does; docs/design/dem.md."},
     {"min_dem_steps", &RveParams::min_dem_steps, Unit::Dimensionless, common::in_cc(1, 1e6),
      Source::job_default,
      "The fewest DEM steps of one RVE step: an increment whose T_p is shorter than this many DEM "
      "steps runs over this many (never longer than the MPM step with rate = \"material\"), so "
      "that an RVE in a slow or static part relaxes between MPM steps instead of running one DEM "
      "step per MPM step (docs/design/rve_step.md, \"The fewest DEM steps\"). 1: no minimum."},
     {"max_steps_per_call", &RveParams::max_steps_per_call, Unit::Dimensionless, common::ge(1),
      Source::cpp_only, "Cap on the DEM steps of one step()."},
     {"initial_pressure", &RveParams::initial_pressure, Unit::Pressure, common::ge(0),
      Source::cpp_only, "> 0: equilibrate isotropically at construction."}});

/// [dem.coupling]: the settings of RveParams that are a name out of a list
/// (common/choice_table.hpp).
inline constexpr common::ChoiceTable<RveParams, 4> kRveChoices{
    "dem.coupling",
    {common::choice<&RveParams::carry_end_forces, kEndForcesNames>(
         "end_forces",
         "The forces that end an RVE step (docs/design/dem.md \"RVE step\"): separate (the "
         "step of older versions: a force evaluation of zero length gives the stress; the next RVE "
         "step computes the forces of the same state again, with its own dt) or carried (the "
         "default: the end state's forces are computed with the step's dt and L, the shear, "
         "rolling and twisting increments of its last DEM step included; they give the stress and "
         "drive the next RVE step's first DEM step: one force evaluation fewer per RVE step, other "
         "bits)."),
     common::choice<&RveParams::rate, kRveRateNames>(
         "rate",
         "How fast an RVE is sheared (docs/design/rve_step.md): material (the default: over "
         "min(T_p, dt), so that its inertial number is the larger of inertial_number and the "
         "material's own, I = |D| d50 sqrt(rho / p): a flow keeps the rate dependence of its "
         "friction, a slow material stays quasi-static) or coupling (always over T_p of eq. 11, at "
         "inertial_number, however fast the material flows: the paper's step)."),
     common::choice<&RveParams::contact_loss, kContactLossNames>(
         "contact_loss",
         "An RVE that has lost every contact (docs/design/rve_step.md): disconnected (the "
         "default: a stress-free material, Dunatunga & Kamrin 2015; a dilation goes to a free "
         "volume and the cell is held; a compression closes the free volume first, then strains "
         "the cell from the state in which it lost its contacts) or strained (the cell follows "
         "every increment, however far a stress-free point is stretched)."),
     common::choice<&RveParams::free_flight, kFreeFlightNames>(
         "free_flight",
         "An RVE step of an RVE without contacts (docs/design/rve_step.md \"Free flight\"): "
         "stepped (the default: its n DEM steps, as an RVE with contacts) or one_step (one DEM "
         "step of the whole step's time when no pair can come into contact within it: the "
         "spheres fly freely, so one step moves them as the n would, to rounding; a step in which "
         "a collision may happen is stepped). Saves the DEM steps of the flow's contact-free "
         "RVEs with contact_loss = \"strained\" (or above disconnect_fraction).")}};

/// Bits of StepReport::guards.
enum RveGuard : std::uint32_t {
  kGuardPressureFloor = 1u << 0,  ///< p < p_floor: T_p computed with p_floor
  kGuardStrainSplit = 1u << 1,    ///< more steps than T_p / dt_DEM to bound the strain per step
  kGuardStepCap = 1u << 2,        ///< T_p shortened to max_steps_per_call DEM steps
  kGuardNoContacts = 1u << 3,     ///< no contact at the end of the step (stress is zero)
  kGuardZeroIncrement = 1u << 4,  ///< L dt == 0: one relaxation step of dt_DEM
  kGuardMaterialRate = 1u << 5,   ///< RveRate::material: T_p cut to the MPM step dt
  kGuardDisconnected = 1u << 6,   ///< ContactLoss::disconnected: held, stress-free (no DEM step)
  kGuardMinSteps = 1u << 7,       ///< T_p raised to min_dem_steps DEM steps
  kGuardFreeFlight = 1u << 8,     ///< RveParams::free_flight: one DEM step of T_p, no contact
  /// ContactLoss::strained: a spray (below disconnect_fraction) whose cell the increment would
  /// make thinner than its neighbour search allows took the increment's volume change only
  /// (docs/design/rve_step.md)
  kGuardSprayShape = 1u << 9,
};

/// What one RVE step did.
struct StepReport {
  std::int64_t dem_steps = 0;  ///< DEM steps done [-]
  double t_p = 0.0;            ///< quasi-static time T_p [s]
  double dt_dem = 0.0;         ///< DEM time step used [s]
  std::uint32_t guards = 0;    ///< RveGuard bits
  std::uint32_t rebuilds = 0;  ///< neighbour-list builds during the DEM steps [-]
  double p = 0.0;              ///< mean pressure, compression positive [Pa]
  double q = 0.0;              ///< deviatoric stress sqrt(3/2 s:s) [Pa]
  double void_ratio = 0.0;     ///< [-]
  double z = 0.0;              ///< coordination number 2 Nc / N [-]
  double wall_s = 0.0;         ///< wall-clock seconds of the step [s]
};

class Rve {
 public:
  /// Build from a packing (spheres at rest, contacts detected, optional equilibration).
  Rve(const Packing& packing, const RveParams& params);
  /// Wrap an already prepared simulation (contact history kept: shear forces and moments).
  /// `params.initial_pressure` is ignored (nothing is re-equilibrated).
  /// The RVE of a prepared simulation, with params' adaptive skin (Numerics::skin_min_factor).
  [[nodiscard]] static Rve from_simulation(Simulation sim, const RveParams& params);

  /// Deform the cell by the increment L dt over T_p = max(max|L dt| / I sqrt(rho d50^2 / p),
  /// dt_DEM), with RveRate::material at most dt: the cell runs with L_DEM = L dt / T_p for
  /// n = T_p / dt_DEM whole steps. With ContactLoss::disconnected, an RVE without contacts takes a
  /// dilation as free volume (no DEM step) and a compression closes it before the cell moves.
  /// @param l  velocity gradient (v = L x, spin included) [1/s]  @param dt MPM step [s], >= 0
  /// @post stress() is the Love-Weber stress at the end, tension positive [Pa]
  StepReport step(const common::Mat3& l, double dt);

  /// Love-Weber Cauchy stress, tension positive [Pa].
  [[nodiscard]] common::Mat3 stress() const { return sim_.stress(); }
  /// The measures of the current state (p, q, void ratio, Z, kGuardNoContacts); the step fields
  /// (dem_steps, t_p, dt_dem, wall_s) stay zero. step() reports the same at its end.
  [[nodiscard]] StepReport measure() const;
  /// Cost proxy: number of spheres.
  [[nodiscard]] std::size_t num_spheres() const { return sim_.spheres().size(); }
  [[nodiscard]] const RveParams& params() const { return params_; }
  [[nodiscard]] double d50() const { return d50_; }  ///< [m]

  /// Full state as named fields ("spheres/x", "contacts/shear_force", ...; docs/design/dem.md).
  void save(common::StateWriter& w) const;
  /// Restore a saved RVE; it continues bit for bit.
  [[nodiscard]] static Rve load(const common::StateReader& r);

  [[nodiscard]] const Simulation& simulation() const { return sim_; }
  Simulation& simulation() { return sim_; }

  /// The critical time step of the last computation and what it was computed for (part of the
  /// state: saved and loaded, so that a restart continues bit for bit). The state is assumed to
  /// change only through step() between computations (simulation() gives write access for
  /// tests and preparation, which run before the first step()).
  struct DtCache {
    double critical_dt = 0.0;    ///< [s]; 0: none (computed at the next step())
    std::int64_t dem_steps = 0;  ///< DEM steps run since [-]
    std::int64_t contacts = 0;   ///< contacts in the state it was computed for [-]
  };
  [[nodiscard]] const DtCache& dt_cache() const { return dt_cache_; }
  /// ContactLoss::disconnected: ln of the material's volume over the cell's since the RVE lost its
  /// contacts (> 0: disconnected and held) [-]. Part of the state.
  [[nodiscard]] double free_volume() const { return free_volume_; }
  /// A dilute material, a spray of grains: its solid fraction (the cell's, diluted by the free
  /// volume of ContactLoss::disconnected) below disconnect_fraction. Its volume carries no lasting
  /// force (docs/design/rve_step.md, "An RVE without contacts").
  [[nodiscard]] bool dilute() const;

 private:
  Rve(Simulation sim, const RveParams& params, double d50);
  /// The critical time step for this step(): the cached one, or computed anew (dt_refresh).
  double critical_dt_for_step();
  /// ContactLoss::disconnected: moves the dilation of `g` into the free volume while the RVE has
  /// no contact, and cuts a compression by the free volume it closes. True: the RVE is held.
  bool take_free_volume(common::Mat3& g);
  /// T_p of eq. (11) for the increment g over the MPM step dt (guards of the rate, the pressure
  /// floor and the minimum of DEM steps into rep.guards).
  double relaxation_time(const common::Mat3& g, double dt, double dt_dem, StepReport& rep) const;
  /// The DEM steps over T_p: enough for dt_dem and the strain split, at most the cap (which then
  /// shortens t_p); the zero-increment, strain-split and cap guards into rep.guards.
  std::int64_t dem_step_count(const common::Mat3& g, double dt_dem, double& t_p,
                              StepReport& rep) const;
  /// RveParams::free_flight: whether the increment g over t_p may run as one DEM step (no
  /// contact, and none can form within it: free_flight_holds).
  [[nodiscard]] bool one_free_step(const common::Mat3& g, double t_p) const;
  /// Runs n DEM steps of t_p / n under the rate g / t_p, with the end forces as configured.
  void run_dem_steps(const common::Mat3& g, double t_p, std::int64_t n);
  /// The DEM part of step(): T_p, the step count, free flight, the DEM steps (their guards, count
  /// and t_p into rep).
  void advance(const common::Mat3& g, double dt, StepReport& rep);
  /// ContactLoss::strained, a solid fraction below disconnect_fraction, and a cell that (I + g)
  /// would bring within 10 % of the neighbour search's limit with the widest skin, (2 +
  /// verlet_skin) r_max: a spray whose cell would become too thin for its spheres.
  [[nodiscard]] bool spray_too_thin_after(const common::Mat3& g) const;

  Simulation sim_;
  RveParams params_;
  double d50_ = 0.0;
  DtCache dt_cache_;
  /// carry_end_forces: the spheres' forces are those of the current state, computed by the last
  /// step() with its dt and L (part of the state; false after construction).
  bool forces_carried_ = false;
  /// ln(V_material / V_cell) >= 0 of ContactLoss::disconnected [-].
  double free_volume_ = 0.0;
};

/// Mass-median diameter of a set of radii [m].
[[nodiscard]] double mass_median_diameter(const std::vector<double>& radii);

}  // namespace dem
