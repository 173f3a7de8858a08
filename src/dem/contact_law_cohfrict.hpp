// Linear elastic-frictional contact with elastic-plastic rolling and twisting resistance, as YADE's
// Law2_ScGeom6D_CohFrictPhys_CohesionMoment (incremental form, no cohesion). Aboul Hosn et al. 2017,
// Granular Matter 19(1); see docs/dem.md and the reference README sections 1-3.
#pragma once

#include <Eigen/Dense>

#include "common/types.hpp"
#include "dem/params.hpp"

namespace dem {

/// Constant properties of one contact, fixed when it is created.
struct CohFrictProps {
  double kn = 0.0;         ///< normal stiffness [N/m]
  double ks = 0.0;         ///< shear stiffness [N/m]
  double kr = 0.0;         ///< rolling stiffness [N m/rad]
  double kt = 0.0;         ///< twisting stiffness [N m/rad]
  double tan_phi = 0.0;    ///< Coulomb coefficient [-]
  double roll_cap = -1.0;  ///< eta_r min(R1, R2) [m]; < 0: no cap
  double twist_cap = -1.0; ///< eta_t min(R1, R2) [m]; < 0: no cap
};

/// History of one contact, carried from step to step.
struct CohFrictHistory {
  common::Vec3 normal;  ///< unit normal from 1 to 2 of the previous step [-]
  common::Vec3 shear;   ///< shear force on sphere 2 [N]
  common::Vec3 roll;    ///< rolling moment on sphere 2 [N m]
  common::Vec3 twist;   ///< twisting moment on sphere 2 [N m]
};

/// Kinematics of one contact this step (what the law sees of the two spheres).
struct ContactKinematics {
  common::Vec3 d;       ///< branch x2 + H k - x1 [m]
  common::Vec3 dv;      ///< relative translational velocity v2 + L s - v1 = u2 - u1 + L d [m/s]
  common::Vec3 w1, w2;  ///< spins [rad/s]
  double r1, r2;        ///< radii [m]
};

/// What the law gives back: force on sphere 2 at the contact point and the torques.
struct ContactResult {
  common::Vec3 force;     ///< total force on sphere 2 (sphere 1 gets the opposite) [N]
  common::Vec3 torque1;   ///< torque on sphere 1 [N m]
  common::Vec3 torque2;   ///< torque on sphere 2 [N m]
  double fn = 0.0;        ///< normal force magnitude [N]
};

/// The contact law functor. Stateless apart from the material; all history lives in the contact.
class CohFrictLaw {
 public:
  explicit CohFrictLaw(const Material& mat);

  /// Properties of a new contact between radii r1, r2 [m].
  [[nodiscard]] CohFrictProps create(double r1, double r2) const;

  /// One step of the law for a contact in overlap (delta = r1 + r2 - |d| > 0).
  /// @param is_new  true on the step the contact is created (history is reset, no rotation)
  /// @param dt      time step [s]
  void apply(const CohFrictProps& props, CohFrictHistory& hist, const ContactKinematics& kin,
             bool is_new, double dt, ContactResult& out) const;

  [[nodiscard]] const Material& material() const { return mat_; }
  /// Change the friction angle used for new contacts [deg].
  void set_friction_deg(double phi_deg);

 private:
  Material mat_;
  double tan_phi_ = 0.0;
};

}  // namespace dem
