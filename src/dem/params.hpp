// Plain parameter structs of the DEM module (units in the field comments) and their parameter
// tables (common/param_table.hpp): the one home of each setting's job key, unit, range, default
// and meaning. The app maps the job file onto the structs through the tables; dem parses no job
// file. Contact law: Aboul Hosn et al. 2017, Granular Matter 19(1).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "common/choice_table.hpp"
#include "common/param_table.hpp"

namespace dem {

/// The contact law of a material: the linear CohFrict law (YADE
/// Law2_ScGeom6D_CohFrictPhys_CohesionMoment, Aboul Hosn et al. 2017) or Hertz-Mindlin (YADE
/// Law2_ScGeom_MindlinPhys_Mindlin with its moments). Job key dem.material.contact_law.
enum class ContactLawKind : std::int8_t { cohfrict = 0, hertz_mindlin = 1 };
/// The job file's names of the laws.
inline constexpr std::array<common::Named<ContactLawKind>, 2> kContactLawNames{
    {{"cohfrict", ContactLawKind::cohfrict}, {"hertz_mindlin", ContactLawKind::hertz_mindlin}}};

/// Hertz-Mindlin parameters (YADE FrictMat and Ip2_FrictMat_FrictMat_MindlinPhys, one material):
/// kno = 4/3 E* sqrt(R*), kso = 2 sqrt(4 R*) G / (2 - nu) with E* = E / (2 (1 - nu^2)),
/// G = E / (2 (1 + nu)), R* = R1 R2 / (R1 + R2); Fn = kno delta^1.5, tangent ks = kso delta^0.5.
/// The defaults are placeholders: a job gives every entry (kHertzMindlin).
struct HertzMindlinMaterial {
  double poisson = -1.0;  ///< Poisson's ratio nu of the grains [-], in [0, 0.5)
  double krot = 0.0;      ///< rolling stiffness kr [N m/rad] (YADE krot), the same for every pair
  double ktwist = 0.0;    ///< twisting stiffness [N m/rad] (YADE ktwist); no cap
  double eta = 0.0;       ///< rolling strength: |Mb| <= eta (R1 + R2)/2 Fn; 0: no cap (YADE)
};

/// One material for all spheres (YADE terms in brackets): the CohFrictMat without cohesion of
/// Aboul Hosn et al. 2017 (the default), or Hertz-Mindlin (`law`, `hm`). The defaults are
/// placeholders: the job file must give every entry of the law's tables (kMaterial, and kCohFrict
/// or kHertzMindlin).
struct Material {
  double density = 0.0;  ///< rho [kg/m^3]
  double young = 0.0;    ///< E [Pa]; CohFrict: k_n = 2 E R1 R2 / (R1 + R2) [N/m]; Hertz: grains' E
  double friction_deg = 0.0;  ///< inter-particle friction angle phi [deg], in [0, 90)
  // CohFrict only (kCohFrict).
  double ks_over_kn = 0.0;  ///< k_s / k_n [-] (YADE `poisson`)
  double alpha_r = 0.0;     ///< rolling stiffness coefficient [-]: k_r = alpha_r k_s R1 R2
  double eta_r = -1.0;      ///< rolling strength coefficient [-]; < 0: no cap
  double alpha_t = 0.0;     ///< twisting stiffness coefficient [-]: k_t = alpha_t k_s R1 R2
  double eta_t = -1.0;      ///< twisting strength coefficient [-]; < 0: no cap
  ContactLawKind law = ContactLawKind::cohfrict;
  HertzMindlinMaterial hm;  ///< Hertz-Mindlin only (kHertzMindlin)

  /// Throws common::InputError naming the job key of the first invalid entry (kMaterial, then
  /// the law's table).
  void validate() const;
};

/// [dem.material]: the settings of Material that are a name out of a list
/// (common/choice_table.hpp).
inline constexpr common::ChoiceTable<Material, 1> kMaterialChoices{
    "dem.material",
    {common::choice<&Material::law, kContactLawNames>(
        "contact_law",
        "The contact law: cohfrict (YADE Law2_ScGeom6D_CohFrictPhys_CohesionMoment, linear, with "
        "rolling resistance: the keys below marked cohfrict) or hertz_mindlin (YADE "
        "Law2_ScGeom_MindlinPhys_Mindlin with its moments: [dem.material.hertz_mindlin]); "
        "docs/design/dem.md \"Contact laws\".")}};

/// "cohfrict", "hertz_mindlin": the job file's name of a law (kContactLawNames).
[[nodiscard]] constexpr std::string_view contact_law_name(ContactLawKind k) {
  return common::name_of(kContactLawNames, k);
}

/// Numerical parameters of the integrator and neighbour search. The member initializers are the
/// defaults of the job keys too (kNumerics).
struct Numerics {
  double damping = 0.2;           ///< Cundall non-viscous damping lambda [-], in [0, 1)
  double dt_safety = 0.8;         ///< safety factor on the global-stiffness critical step [-]
  double skin_factor = 0.1;       ///< Verlet skin as a fraction of the largest radius [-]
  double skin_min_factor = 0.03;  ///< > 0: the skin adapts in [this, skin_factor] r_max [-]
  /// DEM steps between critical time step refreshes of a standalone sample [-] (preparation,
  /// loading; YADE's GlobalStiffnessTimeStepper.timeStepUpdateInterval). An RVE's: RveParams.
  std::int64_t timestep_update_interval = 100;
  double max_skew = 0.5;  ///< re-map the cell when |c_b . c_a| / |c_a|^2 exceeds this [-]

  /// Throws common::InputError naming the job key of the first invalid entry (kNumerics).
  void validate() const;
};

using common::Source;
using common::Unit;

/// [dem.material]: the rows of every law.
inline constexpr auto kMaterial = common::make_table<Material>(
    "dem::Material", "dem.material",
    {{"density", &Material::density, Unit::Density, common::gt(0), Source::job_required,
      "Grain density rho."},
     {"young_modulus", &Material::young, Unit::Pressure, common::gt(0), Source::job_required,
      "cohfrict: the contact modulus E, kn = 2 E R1 R2 / (R1 + R2). hertz_mindlin: the grains' "
      "Young modulus E."},
     {"friction_angle", &Material::friction_deg, Unit::Angle, common::in_co(0, 90),
      Source::job_required, "Inter-particle friction angle phi."}});

/// [dem.material], contact_law = "cohfrict": YADE CohFrictMat with rolling resistance, Aboul Hosn
/// et al. 2017. Required with that law (a job rule), refused with another.
inline constexpr auto kCohFrict = common::make_table<Material>(
    "dem::Material", "dem.material",
    {{"stiffness_ratio", &Material::ks_over_kn, Unit::Dimensionless, common::gt(0),
      Source::job_required, "cohfrict: ks / kn (YADE's `poisson`)."},
     {"rolling_stiffness", &Material::alpha_r, Unit::Dimensionless, common::ge(0),
      Source::job_required, "cohfrict: alpha_r, kr = alpha_r ks R1 R2."},
     {"rolling_strength", &Material::eta_r, Unit::Dimensionless, common::any(),
      Source::job_required,
      "cohfrict: eta_r, |Mr| <= eta_r min(R1, R2) Fn; a negative value means no cap (purely "
      "elastic)."},
     {"twisting.stiffness", &Material::alpha_t, Unit::Dimensionless, common::ge(0),
      Source::job_required, "alpha_t: kt = alpha_t ks R1 R2."},
     {"twisting.strength", &Material::eta_t, Unit::Dimensionless, common::any(),
      Source::job_required, "eta_t: twisting cap coefficient; negative: no cap."}});

/// [dem.material.hertz_mindlin]: YADE's Hertz-Mindlin law with its moments (contact_law =
/// "hertz_mindlin").
inline constexpr auto kHertzMindlin = common::make_table<HertzMindlinMaterial>(
    "dem::HertzMindlinMaterial", "dem.material.hertz_mindlin",
    {{"poisson_ratio", &HertzMindlinMaterial::poisson, Unit::Dimensionless, common::in_co(0, 0.5),
      Source::job_required,
      "Poisson's ratio nu of the grains: kno = 4/3 E/(2 (1 - nu^2)) sqrt(R*), kso = 2 sqrt(4 R*) "
      "G / (2 - nu), G = E / (2 (1 + nu)), R* = R1 R2 / (R1 + R2)."},
     {"rolling_stiffness", &HertzMindlinMaterial::krot, Unit::RotationalStiffness, common::ge(0),
      Source::job_required,
      "kr, the same for every pair (YADE's krot): the bending moment grows by kr times the "
      "relative rolling rotation; 0: no rolling moment."},
     {"rolling_strength", &HertzMindlinMaterial::eta, Unit::Dimensionless, common::ge(0),
      Source::job_required,
      "eta: |Mb| <= eta (R1 + R2) / 2 Fn (YADE's eta); 0: no cap, as in YADE."},
     {"twisting_stiffness", &HertzMindlinMaterial::ktwist, Unit::RotationalStiffness, common::ge(0),
      Source::job_required,
      "kt, the same for every pair (YADE's ktwist); the twisting moment has no cap. 0: none."}});

/// A contact law whose parameters are a table of their own, [dem.material.<name>] (every law
/// but CohFrict, whose keys sit in [dem.material] itself): all that the job's reading, its
/// rules, the schema, validation and the checkpoint (its rows, under
/// params/material/<name>/, common/state_params.hpp) need to know of it. A new law is its
/// ContactLawKind and name, its parameter struct (a member of Material) with its table, and one
/// entry of for_each_table_law; docs/design/dem.md "Contact laws".
template <class P, std::size_t N>
struct TableLaw {
  ContactLawKind kind;
  P Material::*params;                    ///< where Material keeps the law's parameters
  const common::ParamTable<P, N>& table;  ///< its [dem.material.<name>] rows
  std::string_view doc;                   ///< the schema's text of the section

  [[nodiscard]] std::string_view name() const { return contact_law_name(kind); }
  /// "dem.material.hertz_mindlin"
  [[nodiscard]] std::string_view section() const { return table.section; }
};

/// Calls f(law) for every TableLaw, in the order of ContactLawKind.
template <class F>
constexpr void for_each_table_law(F&& f) {
  f(TableLaw{ContactLawKind::hertz_mindlin, &Material::hm, kHertzMindlin,
             "Hertz-Mindlin parameters (YADE FrictMat and Ip2_FrictMat_FrictMat_MindlinPhys). "
             "Required with contact_law = \"hertz_mindlin\", refused with another law."});
}

/// [dem.numerics]: the defaults are the member initializers of Numerics.
inline constexpr auto kNumerics = common::make_table<Numerics>(
    "dem::Numerics", "dem.numerics",
    {{"damping", &Numerics::damping, Unit::Dimensionless, common::in_co(0, 1), Source::job_default,
      "Cundall non-viscous damping coefficient lambda."},
     {"timestep_safety", &Numerics::dt_safety, Unit::Dimensionless, common::in_cc(0.01, 1),
      Source::job_default,
      "Fraction of the critical time step used. At least 0.01: below, the DEM steps grow with no "
      "gain (1e-300 stalled the sample's preparation for 2,000,000 steps)."},
     {"verlet_skin", &Numerics::skin_factor, Unit::Dimensionless, common::in_oc(0, 1),
      Source::job_default,
      "Verlet skin as a fraction of the largest radius: the neighbour list keeps pairs whose gap "
      "is below it and is rebuilt when motion could close it (speed and round-off, not "
      "physics). At most 1 (a skin of one radius: a list of most of the cell's neighbours)."},
     {"verlet_skin_min", &Numerics::skin_min_factor, Unit::Dimensionless, common::in_cc(0, 1),
      Source::job_default,
      "0: the skin is verlet_skin (the fixed skin of older versions). Above 0: each RVE adapts its "
      "skin between "
      "this fraction of "
      "the largest radius and verlet_skin to how fast its spheres move (thin when they barely "
      "move, fewer pairs; wide in a flow, fewer rebuilds), from its own state: restarts, ranks "
      "and threads keep their bits (docs/design/dem.md \"Neighbour search\")."},
     {"timestep_update_interval", &Numerics::timestep_update_interval, Unit::Dimensionless,
      common::ge(1), Source::cpp_only, "Steps between critical time step refreshes."},
     {"max_skew", &Numerics::max_skew, Unit::Dimensionless, common::ge(0.5), Source::cpp_only,
      "Re-map the cell when |c_b . c_a| / |c_a|^2 exceeds this."}});

}  // namespace dem
