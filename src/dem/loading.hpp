// Loading of the periodic cell: imposed velocity gradient, mixed strain-rate / stress control by a
// PI servo on the diagonal strain rates (drained triaxial, isotropic compaction), and sample
// preparation (random cloud from a PSD, compaction with lowered friction, re-equilibration).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "common/choice_table.hpp"
#include "common/types.hpp"
#include "dem/measures.hpp"
#include "dem/packing_io.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// The loading programme of a pure DEM test (`mpmxdem dem`; job key dem.loading.type).
enum class LoadingType : std::uint8_t {
  triaxial,     ///< drained: z compressed, x and y at the confining pressure
  biaxial,      ///< plane strain: z compressed, x at the confining pressure, zero strain on y
  isotropic,    ///< isotropic compression to the confining pressure
  strain_path,  ///< an imposed velocity gradient over a duration
};
/// The job's names of the programmes.
inline constexpr std::array<common::Named<LoadingType>, 4> kLoadingTypeNames{
    {{"triaxial", LoadingType::triaxial},
     {"biaxial", LoadingType::biaxial},
     {"isotropic", LoadingType::isotropic},
     {"strain_path", LoadingType::strain_path}}};

/// [dem.loading]: the settings of the loading programme that are a name out of a list.
struct LoadingProgramme {
  LoadingType type = LoadingType::triaxial;  ///< a placeholder: the job must give the key
};

/// [dem.loading]: the choice rows of LoadingProgramme (common/choice_table.hpp).
inline constexpr common::ChoiceTable<LoadingProgramme, 1> kLoadingChoices{
    "dem.loading",
    {common::required(common::choice<&LoadingProgramme::type, kLoadingTypeNames>(
        "type",
        "What to do after preparation: triaxial (z compressed, x and y at the confining "
        "pressure), biaxial (plane strain: z compressed, x at the confining pressure, zero strain "
        "on y), isotropic, strain_path."))}};

/// "triaxial", "biaxial", ...: the job's name of a programme (kLoadingTypeNames).
[[nodiscard]] constexpr std::string_view loading_type_name(LoadingType t) {
  return common::name_of(kLoadingTypeNames, t);
}

/// Mixed control: diagonal components in `stress_axis` follow a target stress, every other
/// component of L follows `l_imposed`.
struct MixedControl {
  common::Mat3 l_imposed = common::Mat3::Zero();         ///< imposed velocity gradient [1/s]
  std::array<bool, 3> stress_axis{false, false, false};  ///< sigma_aa controlled
  common::Vec3 target = common::Vec3::Zero();            ///< target sigma_aa, tension positive [Pa]
  double max_rate = 1.0;     ///< bound on |L_aa| of stress-controlled axes [1/s]
  double tau_steps = 200.0;  ///< servo time constant, in DEM steps [-]
};

/// PI servo on the cell's diagonal strain rates. The stress error is turned into a strain error
/// with the contact-stiffness modulus M_a = (1/V) sum_c k_n (n_a d_a)^2 (an upper bound of the
/// tangent modulus: the servo is stable and errs on the slow side). When some diagonal rates are
/// imposed (a triaxial's axial rate), a feed-forward adds the rates of the stress-controlled axes
/// that keep their stress constant under the imposed ones in the contact stiffness
/// K_ab = (1/V) sum_c k_n n_a d_a n_b d_b: K_SS r_S = -K_SI L_I (the prediction from the stiffness
/// that YADE's PeriTriaxController makes; docs/design/dem.md, "Stress control"). Without imposed
/// diagonal rates (isotropic compaction) it is off and the servo is the plain PI.
class MixedController {
 public:
  explicit MixedController(const MixedControl& ctl) : ctl_(ctl) {}
  /// Set sim.cell().l from the stress of the last compute_forces(). Deterministic.
  void update(Simulation& sim);
  [[nodiscard]] const MixedControl& control() const { return ctl_; }
  MixedControl& control() { return ctl_; }
  [[nodiscard]] const common::Vec3& integral() const { return integral_; }
  void set_integral(const common::Vec3& v) { integral_ = v; }

 private:
  /// The feed-forward rates of the stress-controlled axes [1/s] (zero without imposed diagonal
  /// rates); p_ref: the stress scale under which an axis counts as without stiffness [Pa].
  [[nodiscard]] common::Vec3 feed_forward(double p_ref) const;

  MixedControl ctl_;
  common::Vec3 integral_ = common::Vec3::Zero();   ///< integral term [1/s]
  common::Vec3 modulus_ = common::Vec3::Zero();    ///< M_a [Pa]
  common::Mat3 stiffness_ = common::Mat3::Zero();  ///< K_ab [Pa]
  std::int64_t last_modulus_step_ = -1;
};

/// Run n steps: forces, servo (if any), integration; refresh dt every
/// numerics().timestep_update_interval steps. `observer` (optional) is called after each step.
void advance(Simulation& sim, MixedController* ctl, std::int64_t n,
             const std::function<void(const Simulation&)>& observer = {});

/// Build a simulation from a packing (spheres at rest); computes contacts and sets dt.
/// Sphere ids follow a spatial order (bins in reduced coordinates), not the file order.
[[nodiscard]] Simulation make_simulation(const Packing& pk, const Material& mat,
                                         const Numerics& num);

/// Re-equilibration under isotropic stress control.
struct EquilibriumTarget {
  double pressure = 1e5;         ///< target p, compression positive [Pa]
  double stress_tol = 0.01;      ///< |sigma_aa - target| / p <= this on every axis [-]
  double unbalanced_tol = 0.01;  ///< unbalanced force ratio below this [-]
  double max_rate = 1.0;         ///< servo strain-rate bound [1/s]
  std::int64_t check_every = 200;
  std::int64_t max_steps = 2000000;
};
/// Called at every check of equilibrate / prepare with the state and its measures (progress).
using CheckObserver = std::function<void(const Simulation&, const Measures&)>;

/// Run isotropic servo steps until the target is met; returns steps done (throws NumericalError
/// if max_steps pass without reaching it). `observe` sees every check (every check_every steps).
std::int64_t equilibrate(Simulation& sim, const EquilibriumTarget& target,
                         const CheckObserver& observe = {});

/// Particle size distribution: diameters [m] ascending with the mass fraction passing [0..1].
struct Psd {
  std::vector<double> diameter;  ///< [m]
  std::vector<double> passing;   ///< mass fraction passing, from 0 to 1, non-decreasing
};

/// Random loose cloud of n non-overlapping spheres in a cubic cell of solid fraction `solid`,
/// radii drawn from the PSD by number (mass weights / d^3). Deterministic for a seed.
[[nodiscard]] Packing make_cloud(const Psd& psd, std::int64_t n, double solid, std::uint64_t seed);

/// Sample preparation. A job gives the friction angle and the target pressure (their
/// initializers are placeholders for C++ users); the tolerances' initializers are the job
/// defaults (kPreparation, kPreparationTarget). The app sets compaction_rate (and
/// target.max_rate) from dem.preparation.inertial_number.
struct Preparation {
  double friction_comp_deg = 1.0;  ///< friction during compaction [deg]
  /// Target void ratio [-]; 0: none. Above 0 the compaction friction is searched for in
  /// [0, friction_comp_deg] until the compacted void ratio is within void_ratio_tol (prepare()).
  double void_ratio = 0.0;
  double void_ratio_tol = 0.003;      ///< absolute tolerance on void_ratio [-]
  std::int64_t max_compactions = 16;  ///< trials of the search towards void_ratio, at most
  EquilibriumTarget target;           ///< target pressure and tolerances
  double compaction_rate = 10.0;      ///< strain-rate bound while compacting [1/s]
};

/// [dem.preparation]: the friction angle of the compaction (the target: kPreparationTarget).
inline constexpr auto kPreparation = common::make_table<Preparation>(
    "dem::Preparation", "dem.preparation",
    {{"friction_angle", &Preparation::friction_comp_deg, Unit::Angle, common::in_co(0, 90),
      Source::job_required, "Friction angle during compaction (controls the void ratio)."},
     {"void_ratio", &Preparation::void_ratio, Unit::Dimensionless, common::gt(0),
      Source::job_optional,
      "Target void ratio of a generated sample: the compaction friction is searched for between "
      "0 and friction_angle (bisection, each trial a compaction of the same cloud, at most 16) "
      "until the compacted void ratio is within void_ratio_tolerance; friction_angle must give a "
      "looser packing. Absent: the compaction at friction_angle alone."},
     {"void_ratio_tolerance", &Preparation::void_ratio_tol, Unit::Dimensionless,
      common::in_oo(0, 1), Source::job_default,
      "Absolute tolerance on void_ratio (a compaction of 100 spheres is chaotic: its void ratio "
      "scatters by about 0.01 between nearby frictions, so a few trials land within 0.003)."},
     {"max_compactions", &Preparation::max_compactions, Unit::Dimensionless, common::ge(1),
      Source::cpp_only, "Compactions the search towards void_ratio tries at most."},
     {"compaction_rate", &Preparation::compaction_rate, Unit::Rate, common::gt(0), Source::cpp_only,
      "Strain-rate bound while compacting."}});

/// [dem.preparation]: the target of Preparation::target (an EquilibriumTarget).
inline constexpr auto kPreparationTarget = common::make_table<EquilibriumTarget>(
    "dem::EquilibriumTarget", "dem.preparation",
    {{"pressure", &EquilibriumTarget::pressure, Unit::Pressure, common::gt(0), Source::job_required,
      "Target confining pressure p0."},
     {"stress_tolerance", &EquilibriumTarget::stress_tol, Unit::Dimensionless, common::in_oo(0, 1),
      Source::job_default, "Relative tolerance on the reached pressure."},
     {"unbalanced_force", &EquilibriumTarget::unbalanced_tol, Unit::Dimensionless,
      common::in_oo(0, 1), Source::job_default,
      "Equilibrium when the unbalanced force ratio is below this."},
     {"max_rate", &EquilibriumTarget::max_rate, Unit::Rate, common::gt(0), Source::cpp_only,
      "Servo strain-rate bound."},
     {"check_every", &EquilibriumTarget::check_every, Unit::Dimensionless, common::ge(1),
      Source::cpp_only, "Steps between two checks of the target."},
     {"max_steps", &EquilibriumTarget::max_steps, Unit::Dimensionless, common::ge(1),
      Source::cpp_only, "Steps after which equilibrate() gives up."}});
/// What prepare() reached.
struct Prepared {
  std::int64_t steps = 0;           ///< DEM steps, every compaction and the re-equilibration
  double friction_deg = 0.0;        ///< the kept compaction's friction [deg]
  double compacted_void_ratio = 0;  ///< void ratio at the end of the kept compaction [-]
  std::int64_t compactions = 0;     ///< compactions of the cloud tried
  /// false when Preparation::void_ratio was not reached within its tolerance: the compaction at
  /// friction_comp_deg is denser than the target (compactions == 1), or none of
  /// max_compactions came within the tolerance (the closest is kept). Always true without a
  /// target.
  bool reached = true;
};

/// Isotropic compaction with lowered friction (towards prep.void_ratio if set: a bisection on the
/// compaction friction between 0 and friction_comp_deg, each trial a compaction of the cloud as
/// given), then friction restored (also on existing contacts) and re-equilibration.
Prepared prepare(Simulation& sim, const Preparation& prep, const CheckObserver& observe = {});

}  // namespace dem

namespace dem {
/// Drained triaxial along z: L_zz = -axial_rate (compression for rate > 0), sigma_xx and sigma_yy
/// held at -confining (tension positive). @param axial_rate [1/s] @param confining [Pa]
[[nodiscard]] MixedControl triaxial_control(double axial_rate, double confining, double max_rate);
}  // namespace dem
