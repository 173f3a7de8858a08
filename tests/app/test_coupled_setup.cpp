// Tests of app::coupled_setup: a job with an elastic and a DEM body maps onto one farm config whose
// micro kind creates the right model for each point id, restores each from its saved state, and
// takes its knobs from the job.
#include "app/setup/coupled_setup.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/errors.hpp"
#include "common/state_store.hpp"
#include "farm/dem_micro.hpp"
#include "farm/elastic_micro.hpp"

namespace {
const char* kJob = R"([dem.material]
density = "2650 kg/m^3"
young_modulus = "300 MPa"
stiffness_ratio = 0.5
friction_angle = "30 deg"
rolling_stiffness = 2.0
rolling_strength = 0.3

[dem.sample]
spheres = 60
psd_diameters = ["130 um", "270 um"]
psd_passing = [0.0, 1.0]
seed = 5

[dem.preparation]
pressure = "100 kPa"
friction_angle = "10 deg"
inertial_number = 1e-2
unbalanced_force = 0.05
stress_tolerance = 0.02

[dem.coupling]
inertial_number = 1e-2
pressure_floor = "2 kPa"

[mpm]
end_time = 1.0
dt = 1e-3

[mpm.grid]
origin = [0.0, 0.0, 0.0]
spacing = [1.0, 1.0, 1.0]
cells = [2, 1, 1]

[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]
points_per_cell = 1
density = 1696.0
material = "dem"

[[mpm.body]]
min = [1.0, 0.0, 0.0]
max = [2.0, 1.0, 1.0]
points_per_cell = 1
density = 2000.0
material = "elastic"
initial_stress = ["-50 kPa", "-50 kPa", "-50 kPa", 0.0, 0.0, 0.0]

[mpm.elastic]
young_modulus = "50 MPa"
poisson_ratio = 0.3

[output]
every = 3
checkpoint_every = 7
checkpoint_keep = 3
progress_interval = "2 s"

[farm]
rebalance_threshold = 1.5
rebalance_check_every = 11
wait = "sleep"
rank0_rves = false
)";

TEST(CoupledSetup, MapsKnobsAndPointsOfTheJob) {
  const app::Job job = app::Job::parse(kJob, "mixed.toml");
  const farm::CoupledConfig c = app::coupled_setup(job, {"out", 40});
  ASSERT_EQ(c.points.size(), 2U);
  for (auto m : c.points.material) EXPECT_EQ(m, 0);  // the farm is the one material
  EXPECT_EQ(c.max_steps, 40);
  EXPECT_DOUBLE_EQ(c.end_time, 1.0);
  EXPECT_EQ(c.output.dir, "out");
  EXPECT_EQ(c.output.every, 3);
  EXPECT_DOUBLE_EQ(c.output.log_every_s, 2.0);
  EXPECT_EQ(c.checkpoint.every_steps, 7);
  EXPECT_EQ(c.checkpoint.keep, 3);
  EXPECT_DOUBLE_EQ(c.balance.threshold, 1.5);
  EXPECT_EQ(c.balance.check_every, 11);
  EXPECT_EQ(c.farm.wait, farm::WaitMode::sleep);
  EXPECT_FALSE(c.farm.rank0_rves);  // a TOML boolean, a flag row of kFarmChoices
  EXPECT_EQ(c.job_text, std::string(kJob));
  // Keys the job leaves out take the C++ defaults (one home: the parameter tables).
  EXPECT_EQ(c.checkpoint.every_wall_s, farm::CheckpointOptions{}.every_wall_s);
  EXPECT_EQ(c.solver.dt, 1e-3);
  EXPECT_EQ(c.solver.cfl, mpm::SolverConfig{}.cfl);
  EXPECT_EQ(c.solver.flip, mpm::SolverConfig{}.flip);
  EXPECT_EQ(c.solver.damping, mpm::SolverConfig{}.damping);
  EXPECT_EQ(c.solver.mass_threshold, mpm::SolverConfig{}.mass_threshold);
}

// [output.grains] without `every` takes the C++ default, and the schema says the same number (it
// said 100 while GrainViewOptions said 10).
TEST(CoupledSetup, GrainViewsWithoutEveryTakeTheOneDefault) {
  std::string text = kJob;
  text += "\n[output.grains]\nrves = [0]\n";
  const farm::CoupledConfig c =
      app::coupled_setup(app::Job::parse(text, "grains.toml"), {"out", 4});
  ASSERT_EQ(c.grains.rves, std::vector<std::int64_t>{0});
  EXPECT_EQ(c.grains.every, farm::GrainViewOptions{}.every);
  EXPECT_EQ(c.grains.every, 100);
  const std::string with = text + "every = 7\n";
  EXPECT_EQ(app::coupled_setup(app::Job::parse(with, "grains.toml"), {"out", 4}).grains.every, 7);
}

TEST(CoupledSetup, CreatesAndRestoresTheModelOfEachPoint) {
  const app::Job job = app::Job::parse(kJob, "mixed.toml");
  const farm::CoupledConfig c = app::coupled_setup(job, {"out", -1});
  EXPECT_EQ(c.max_steps, 0);  // no limit
  const std::int64_t dem_id = c.points.id[c.points.x[0].x() < 1.0 ? 0 : 1];
  const std::int64_t elastic_id = c.points.id[c.points.x[0].x() < 1.0 ? 1 : 0];

  auto dem = c.micro.create(dem_id);
  auto* as_dem = dynamic_cast<farm::DemMicro*>(dem.get());
  ASSERT_NE(as_dem, nullptr);
  // The prepared sample: p at the preparation pressure, the coupling parameters of the job.
  const common::Mat3 s = dem->stress();
  EXPECT_NEAR(-s.trace() / 3.0, 1e5, 0.03e5);
  EXPECT_DOUBLE_EQ(as_dem->rve().params().inertial_number, 1e-2);
  EXPECT_DOUBLE_EQ(as_dem->rve().params().p_floor, 2e3);
  // Keys the job leaves out take the C++ defaults (one home: dem's parameter tables).
  EXPECT_EQ(as_dem->rve().params().max_strain_per_step, dem::RveParams{}.max_strain_per_step);
  EXPECT_EQ(as_dem->rve().params().numerics.skin_factor, dem::Numerics{}.skin_factor);
  EXPECT_EQ(as_dem->rve().params().numerics.damping, dem::Numerics{}.damping);
  EXPECT_NEAR(as_dem->rve().d50(), 2e-4, 1e-12);  // PSD linear in mass between 130 and 270 um
  // A second RVE of the rank is a copy of the same prototype.
  EXPECT_EQ(c.micro.create(dem_id)->stress(), s);

  auto elastic = c.micro.create(elastic_id);
  ASSERT_NE(dynamic_cast<farm::ElasticMicro*>(elastic.get()), nullptr);
  EXPECT_EQ(elastic->stress(), -5e4 * common::Mat3::Identity());

  // Restore dispatches on the saved fields.
  for (auto* m : {dem.get(), elastic.get()}) {
    common::StateStore store;
    m->save(store);
    auto back = c.micro.load(store);
    EXPECT_EQ(typeid(*back), typeid(*m));
    EXPECT_EQ(back->stress(), m->stress());
  }
}

}  // namespace

namespace {

const char* kFrictionalJob = R"([mpm]
end_time = 1.0
[mpm.elastic]
young_modulus = "10 MPa"
poisson_ratio = 0.3
friction_angle = "38.3 deg"
residual_friction_angle = "0.48 rad"
softening_strain = 0.05
[mpm.grid]
origin = [0.0, 0.0, 0.0]
spacing = [1.0, 1.0, 1.0]
cells = [1, 1, 1]
[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 1.0]
points_per_cell = 1
density = 1000.0
material = "elastic"
initial_stress = ["-10 kPa", "-10 kPa", "-10 kPa", 0.0, 0.0, 0.0]
)";

}  // namespace

// [mpm.elastic] fills farm::ElasticMaterial through its table: the angles in degrees as the job
// gives them (a value in radians converted by the job's units), the absent dilatancy 0; the model
// is the one of those parameters, stress for stress.
TEST(CoupledSetup, ElasticMaterialComesFromItsTable) {
  const farm::CoupledConfig c =
      app::coupled_setup(app::Job::parse(kFrictionalJob, "frictional.toml"), {"out", 4});
  ASSERT_EQ(c.points.size(), 1U);
  auto m = c.micro.create(c.points.id[0]);
  common::StateStore s;
  m->save(s);
  const double residual = s.read_f64("elastic/params/residual_friction_angle").at(0);
  EXPECT_EQ(s.read_f64("elastic/params/young_modulus"), std::vector<double>{10e6});
  EXPECT_EQ(s.read_f64("elastic/params/poisson_ratio"), std::vector<double>{0.3});
  EXPECT_EQ(s.read_f64("elastic/params/friction_angle"), std::vector<double>{38.3});
  EXPECT_EQ(s.read_f64("elastic/params/dilatancy_angle"), std::vector<double>{0.0});
  EXPECT_NEAR(residual, 0.48 * 180.0 / M_PI, 1e-12);
  EXPECT_EQ(s.read_f64("elastic/params/softening_strain"), std::vector<double>{0.05});

  farm::ElasticMicroParams p;
  p.material.young_modulus = 10e6;
  p.material.poisson_ratio = 0.3;
  p.material.friction_deg = 38.3;
  p.material.residual_friction_deg = residual;
  p.material.softening_strain = 0.05;
  p.density = 1000.0;
  farm::ElasticMicro direct(c.points.id[0], p, -1e4 * common::Mat3::Identity());
  common::Mat3 L = common::Mat3::Zero();
  L(0, 2) = 1.0;
  for (int k = 0; k < 200; ++k) {
    (void)m->step(L, 1e-4);
    (void)direct.step(L, 1e-4);
  }
  EXPECT_TRUE(m->stress() == direct.stress());
}
