// dem::ContactLaw: the seam between the force loop and the contact laws. It holds the material's
// law (Material::law) and forwards each call to it with one switch per call: the force loop calls
// apply_batch once per run of CohFrictBatch::kLanes pairs, so there is no per-contact dispatch and
// each law keeps its own vectorised lane loop. Every law shares the pair arrays of Contacts: the
// friction coefficient fixed at creation (tan_phi) and the history (normal, shear force, rolling
// and twisting moments).
//
// Adding a law: its parameters (a struct and parameter table in dem/params.hpp, a name in
// ContactLawKind and contact_law_name), its file (contact_law_<name>.hpp/.cpp: props,
// normal_force, apply_batch, stiffness_lanes, twists), a case in each switch below, and its schema
// rows and job rule (app/job/schema_dem.cpp, app/job/job_rules.cpp). docs/design/architecture.md
// counts the files.
#pragma once

#include <vector>

#include "common/types.hpp"
#include "dem/cohfrict_arrays.hpp"
#include "dem/contact_law_cohfrict.hpp"
#include "dem/contact_law_hertz_mindlin.hpp"
#include "dem/params.hpp"

namespace dem {

class ContactLaw {
 public:
  /// @pre mat valid (Material::validate).
  explicit ContactLaw(const Material& mat) : cohfrict_(mat), hertz_mindlin_(mat) {}

  [[nodiscard]] ContactLawKind kind() const { return cohfrict_.material().law; }
  /// The material, with the current friction angle.
  [[nodiscard]] const Material& material() const { return cohfrict_.material(); }
  /// Friction coefficient of a contact created now.
  [[nodiscard]] double tan_phi() const { return cohfrict_.tan_phi(); }
  /// Change the friction angle used for new contacts [deg].
  /// (Every law reads the coefficient of a contact from Contacts::tan_phi.)
  void set_friction_deg(double phi_deg) { cohfrict_.set_friction_deg(phi_deg); }
  /// Whether contacts may have a twisting stiffness.
  [[nodiscard]] bool twists() const {
    return kind() == ContactLawKind::hertz_mindlin ? hertz_mindlin_.twists() : cohfrict_.twists();
  }
  /// The stiffnesses of a contact of radii r1, r2 [m] at overlap delta [m] created with friction
  /// coefficient tan_phi: constant for CohFrict, tangent at delta for Hertz-Mindlin.
  [[nodiscard]] ContactProps props(double r1, double r2, double delta, double tan_phi) const {
    return kind() == ContactLawKind::hertz_mindlin ? hertz_mindlin_.props(r1, r2, delta, tan_phi)
                                                   : cohfrict_.props(r1, r2, tan_phi);
  }
  /// Normal force magnitude at overlap delta > 0 [N], the bits of the force loop.
  [[nodiscard]] double normal_force(double r1, double r2, double delta) const {
    return kind() == ContactLawKind::hertz_mindlin ? hertz_mindlin_.normal_force(r1, r2, delta)
                                                   : cohfrict_.props(r1, r2, 0.0).kn * delta;
  }
  /// One step of the law for the lanes of a batch (CohFrictLaw::apply_batch's contract).
  void apply_batch(CohFrictBatch& b, const std::vector<double>& tan_phi,
                   CohFrictHistoryArrays& hist, const common::Mat3& l, double dt,
                   bool twist_possible) const {
    if (kind() == ContactLawKind::hertz_mindlin) {
      hertz_mindlin_.apply_batch(b, tan_phi, hist, l, dt, twist_possible);
    } else {
      cohfrict_.apply_batch(b, tan_phi, hist, l, dt, twist_possible);
    }
  }
  /// The stiffness terms of the critical time step (StiffnessLanes; b.delta is read only by
  /// laws whose stiffness depends on the overlap: stiffness_uses_overlap()).
  void stiffness_lanes(StiffnessLanes& b) const {
    if (kind() == ContactLawKind::hertz_mindlin) {
      hertz_mindlin_.stiffness_lanes(b);
    } else {
      dem::stiffness_lanes(material(), b);
    }
  }
  [[nodiscard]] bool stiffness_uses_overlap() const {
    return kind() == ContactLawKind::hertz_mindlin;
  }

 private:
  CohFrictLaw cohfrict_;
  HertzMindlinLaw hertz_mindlin_;
};

}  // namespace dem
