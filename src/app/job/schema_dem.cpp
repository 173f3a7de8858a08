// Job-file sections of the DEM (the RVE): [dem.material], [dem.sample], [dem.preparation],
// [dem.numerics], [dem.coupling], [dem.sparing], [dem.loading]. The material, numerics, coupling,
// sparing and preparation keys are the rows of parameter tables (dem/params.hpp, dem/rve.hpp,
// dem/loading.hpp, farm/spared_micro.hpp).
#include "app/job/schema.hpp"
#include "app/job/schema_params.hpp"
#include "dem/loading.hpp"
#include "dem/params.hpp"
#include "dem/rve.hpp"
#include "farm/spared_micro.hpp"

namespace app {

namespace {

// [dem] and [dem.material]: the contact law and its parameters.
void add_material(Schema& s) {
  s.add("dem", Type::Table,
        "The discrete-element model: of every RVE in `run`, of the sample in `dem`.");

  s.add("dem.material", Type::Table,
        "Grain and contact parameters: the linear CohFrict law with rolling resistance (YADE "
        "CohFrictMat, Aboul Hosn et al. 2017) or Hertz-Mindlin (YADE's Mindlin law).")
      .need();
  add_choices(s, dem::kMaterialChoices);  // contact_law
  add_params(s, dem::kMaterial);
  constexpr std::string_view kWithCohFrict = "with contact_law = \"cohfrict\"";
  add_params(s, dem::kCohFrict, {}, kWithCohFrict);
  s.add("dem.material.twisting", Type::Table,
        "cohfrict: twisting resistance; absent: no twisting moment.");
  add_params(s, dem::kCohFrict, "twisting");
  dem::for_each_table_law([&s](const auto& d) {
    s.add(std::string(d.section()), Type::Table, std::string(d.doc));
    add_params(s, d.table);
  });
}

// [dem.sample] (a packing file or a generated cloud) and [dem.preparation].
void add_sample(Schema& s) {
  using Q = Quantity;
  s.add("dem.sample", Type::Table,
        "The sphere sample: loaded from a packing file, or generated as a cloud.")
      .need();
  s.add("dem.sample.packing", Type::String,
        "Packing text file (x y z r per line, YADE-compatible), relative to the job file. "
        "Absent: a random cloud is generated from `spheres` and the size distribution.");
  s.add("dem.sample.cell", Type::FloatList,
        "Sizes Lx, Ly, Lz of the periodic cell, for a packing file without a CELL or HSIZE line "
        "(YADE's yade.export.text writes none); a cell line of the file that disagrees is "
        "refused (docs/validation/yade_reference.md).")
      .unit(Q::Length)
      .in(0, std::nullopt, true)
      .len(3, 3);
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
  add_params(s, dem::kPreparationTarget);  // pressure, stress_tolerance, unbalanced_force
  add_params(s, dem::kPreparation);        // friction_angle
  s.add("dem.preparation.inertial_number", Type::Float,
        "Inertial number of the compaction strain rate (at least 1e-6: the DEM steps grow as "
        "1 / I).")
      .in(1e-6, 1, false, true)
      .or_default(1e-3);
}

// [dem.numerics], [dem.coupling] (the RVE step) and [dem.sparing].
void add_rve_numerics(Schema& s) {
  s.add("dem.numerics", Type::Table, "Numerical knobs of the DEM.");
  add_params(s, dem::kNumerics);

  s.add("dem.coupling", Type::Table, "The RVE step of MPM x DEM (paper eqs. 11-12).");
  add_params(s, dem::kRveParams);
  add_choices(s, dem::kRveChoices);  // end_forces, rate, contact_loss, free_flight

  s.add("dem.sparing", Type::Table,
        "Sparing of idle RVEs in `run` (docs/design/sparing.md): off unless `tolerance` > 0.");
  add_params(s, farm::kSparingOptions);
}

// [dem.loading]: the loading programme of `mpmxdem dem`.
void add_loading(Schema& s) {
  using Q = Quantity;
  s.add("dem.loading", Type::Table, "The loading programme of a pure DEM job (`mpmxdem dem`).");
  add_choices(s, dem::kLoadingChoices);  // type
  s.add("dem.loading.inertial_number", Type::Float,
        "Inertial number of the imposed strain rate (at least 1e-6: the DEM steps grow as 1 / I, "
        "and below I ~ 1e-3 the response is already quasi-static).")
      .in(1e-6, 1, false, true);
  s.add("dem.loading.axial_strain", Type::Float,
        "Final axial strain (compression positive) of a triaxial or biaxial test.")
      .in(0, 1, true, true);
  s.add("dem.loading.confining_pressure", Type::Float,
        "Lateral stress held by the servo (triaxial: x and y; biaxial: x), or target (isotropic).")
      .unit(Q::Pressure)
      .in(0, std::nullopt, true);
  s.add("dem.loading.lateral_tolerance", Type::Float,
        "A triaxial or biaxial test stops (exit 3) when a lateral stress strays further than this "
        "fraction "
        "from the confining pressure, once the axial strain passes 0.1 % (the servo's start): a "
        "curve whose control failed is never written as if it held.")
      .in(0, std::nullopt, true)
      .or_default(0.05);
  s.add("dem.loading.velocity_gradient", Type::FloatList,
        "Imposed velocity gradient L, row-major (strain_path).")
      .unit(Q::Rate)
      .len(9, 9);
  s.add("dem.loading.duration", Type::Float,
        "Duration of the imposed velocity gradient (strain_path).")
      .unit(Q::Time)
      .in(0, std::nullopt, true);
}

}  // namespace

void add_dem_sections(Schema& s) {
  add_material(s);
  add_sample(s);
  add_rve_numerics(s);
  add_loading(s);
}

}  // namespace app
