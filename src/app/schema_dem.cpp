// Job-file sections of the DEM (the RVE): [dem.material], [dem.sample], [dem.preparation],
// [dem.numerics], [dem.coupling], [dem.loading]. Contact law: ../shared/reference/README.md (YADE).
#include "app/schema.hpp"

namespace app {

void add_dem_sections(Schema& s) {
  using Q = Quantity;
  s.add("dem", Type::Table,
        "The discrete-element model: of every RVE in `run`, of the sample in `dem`.");

  s.add("dem.material", Type::Table,
        "Grain and contact parameters (YADE CohFrictMat with rolling resistance, Aboul Hosn et al. "
        "2017).")
      .need();
  s.add("dem.material.density", Type::Float, "Grain density rho.")
      .unit(Q::Density)
      .in(0, std::nullopt, true)
      .need();
  s.add("dem.material.young_modulus", Type::Float, "Contact modulus E: kn = 2 E R1 R2 / (R1 + R2).")
      .unit(Q::Pressure)
      .in(0, std::nullopt, true)
      .need();
  s.add("dem.material.stiffness_ratio", Type::Float, "ks / kn (YADE's `poisson`).")
      .in(0, std::nullopt, true)
      .need();
  s.add("dem.material.friction_angle", Type::Float, "Inter-particle friction angle phi.")
      .unit(Q::Angle)
      .in(0, 90, false, true)
      .need();
  s.add("dem.material.rolling_stiffness", Type::Float, "alpha_r: kr = alpha_r ks R1 R2.")
      .in(0, std::nullopt)
      .need();
  s.add("dem.material.rolling_strength", Type::Float,
        "eta_r: |Mr| <= eta_r min(R1, R2) Fn; a negative value means no cap (purely elastic).")
      .need();
  s.add("dem.material.twisting", Type::Table, "Twisting resistance; absent: no twisting moment.");
  s.add("dem.material.twisting.stiffness", Type::Float, "alpha_t: kt = alpha_t ks R1 R2.")
      .in(0, std::nullopt)
      .need();
  s.add("dem.material.twisting.strength", Type::Float,
        "eta_t: twisting cap coefficient; negative: no cap.")
      .need();

  s.add("dem.sample", Type::Table,
        "The sphere sample: loaded from a packing file, or generated as a cloud.")
      .need();
  s.add("dem.sample.packing", Type::String,
        "Packing text file (x y z r per line, YADE-compatible), relative to the job file. "
        "Absent: a random cloud is generated from `spheres` and the size distribution.");
  s.add("dem.sample.spheres", Type::Int, "Number of spheres of a generated sample.")
      .in(2, std::nullopt);
  s.add("dem.sample.psd_diameters", Type::FloatList,
        "Particle-size distribution: diameters, increasing.")
      .unit(Q::Length)
      .in(0, std::nullopt, true)
      .len(2, 1000);
  s.add("dem.sample.psd_passing", Type::FloatList,
        "Mass fraction passing at each diameter, non-decreasing from 0 to 1.")
      .in(0, 1)
      .len(2, 1000);
  s.add("dem.sample.seed", Type::Int, "Random seed of the generated cloud.")
      .in(0, std::nullopt)
      .or_default(std::int64_t{1});

  s.add("dem.preparation", Type::Table,
        "Isotropic compaction with a lowered friction angle, friction restored, re-equilibration.")
      .need();
  s.add("dem.preparation.pressure", Type::Float, "Target confining pressure p0.")
      .unit(Q::Pressure)
      .in(0, std::nullopt, true)
      .need();
  s.add("dem.preparation.friction_angle", Type::Float,
        "Friction angle during compaction (controls the void ratio).")
      .unit(Q::Angle)
      .in(0, 90, false, true)
      .need();
  s.add("dem.preparation.stress_tolerance", Type::Float,
        "Relative tolerance on the reached pressure.")
      .in(0, 1, true, true)
      .or_default(0.01);
  s.add("dem.preparation.unbalanced_force", Type::Float,
        "Equilibrium when the unbalanced force ratio is below this.")
      .in(0, 1, true, true)
      .or_default(0.01);
  s.add("dem.preparation.inertial_number", Type::Float,
        "Inertial number of the compaction strain rate.")
      .in(0, 1, true, true)
      .or_default(1e-3);

  s.add("dem.numerics", Type::Table, "Numerical knobs of the DEM.");
  s.add("dem.numerics.damping", Type::Float, "Cundall non-viscous damping coefficient lambda.")
      .in(0, 1, false, true)
      .or_default(0.2);
  s.add("dem.numerics.timestep_safety", Type::Float, "Fraction of the critical time step used.")
      .in(0, 1, true, false)
      .or_default(0.8);
  s.add("dem.numerics.verlet_skin", Type::Float, "Verlet skin as a fraction of the mean radius.")
      .in(0, std::nullopt, true)
      .or_default(0.1);

  s.add("dem.coupling", Type::Table, "The RVE step of MPM x DEM (paper eqs. 11-12).");
  s.add("dem.coupling.inertial_number", Type::Float,
        "Inertial number I_n of the quasi-static time T_p (eq. 11).")
      .in(0, 1, true, true)
      .need();
  s.add("dem.coupling.max_strain_per_step", Type::Float,
        "Guard: largest strain increment of one DEM step.")
      .in(0, 1, true, true)
      .or_default(1e-5);
  s.add("dem.coupling.pressure_floor", Type::Float,
        "Guard: smallest pressure used in T_p (an RVE losing its contacts).")
      .unit(Q::Pressure)
      .in(0, std::nullopt, true)
      .or_default(1e3);

  s.add("dem.loading", Type::Table, "The loading programme of a pure DEM job (`mpmxdem dem`).");
  s.add("dem.loading.type", Type::String, "What to do after preparation.")
      .one_of({"triaxial", "isotropic", "strain_path"})
      .need();
  s.add("dem.loading.inertial_number", Type::Float, "Inertial number of the imposed strain rate.")
      .in(0, 1, true, true);
  s.add("dem.loading.axial_strain", Type::Float,
        "Final axial strain (compression positive) of a triaxial test.")
      .in(0, 1, true, true);
  s.add("dem.loading.confining_pressure", Type::Float,
        "Lateral stress held by the servo (triaxial), or target (isotropic).")
      .unit(Q::Pressure)
      .in(0, std::nullopt, true);
  s.add("dem.loading.velocity_gradient", Type::FloatList,
        "Imposed velocity gradient L, row-major (strain_path).")
      .unit(Q::Rate)
      .len(9, 9);
  s.add("dem.loading.duration", Type::Float,
        "Duration of the imposed velocity gradient (strain_path).")
      .unit(Q::Time)
      .in(0, std::nullopt, true);
}

}  // namespace app
