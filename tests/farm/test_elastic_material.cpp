// Unit tests of farm::ElasticMaterial (farm/elastic_material.hpp): its validation names the job
// keys of its table, and the degrees of an older state's radians give those radians back.
#include "farm/elastic_material.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "common/errors.hpp"

namespace {

farm::ElasticMaterial material() {
  farm::ElasticMaterial m;
  m.young_modulus = 10e6;
  m.poisson_ratio = 0.3;
  return m;
}

std::string error_of(const farm::ElasticMaterial& m) {
  try {
    m.validate();
  } catch (const common::InputError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

// The ranges are the table's, named by job key; the defaults of the optional keys (0: linear
// elastic, no dilatancy, no softening) are in range.
TEST(ElasticMaterial, RangesAreTheTablesNamedByJobKey) {
  EXPECT_EQ(error_of(material()), "");
  farm::ElasticMaterial m = material();
  m.young_modulus = -1.0;
  EXPECT_EQ(error_of(m), "mpm.elastic.young_modulus = -1: must be > 0 Pa");
  m = material();
  m.poisson_ratio = 0.5;
  EXPECT_EQ(error_of(m), "mpm.elastic.poisson_ratio = 0.5: must be in (-1, 0.5)");
  m = material();
  m.friction_deg = 90.0;
  EXPECT_EQ(error_of(m), "mpm.elastic.friction_angle = 90: must be in [0, 90) deg");
  m = material();
  m.softening_strain = -0.1;
  EXPECT_EQ(error_of(m), "mpm.elastic.softening_strain = -0.1: must be >= 0");
  m = material();
  m.dilatancy_deg = std::nan("");
  EXPECT_EQ(error_of(m), "mpm.elastic.dilatancy_angle = nan: must be in [0, 90) deg");
}

// The rules between the angles, as the job rules state them (app/job/job_rules.cpp).
TEST(ElasticMaterial, RulesBetweenTheAngles) {
  farm::ElasticMaterial m = material();
  m.friction_deg = 30.0;
  m.dilatancy_deg = 35.0;
  EXPECT_EQ(error_of(m),
            "mpm.elastic.dilatancy_angle = 35: must be <= mpm.elastic.friction_angle (30 deg)");
  m.dilatancy_deg = 30.0;  // associated flow
  EXPECT_EQ(error_of(m), "");
  m.softening_strain = 0.05;
  EXPECT_EQ(error_of(m),
            "mpm.elastic.dilatancy_angle = 30: must be 0 with "
            "mpm.elastic.softening_strain");
  m.dilatancy_deg = 0.0;
  m.residual_friction_deg = 31.0;
  EXPECT_EQ(error_of(m),
            "mpm.elastic.residual_friction_angle = 31: must be <= "
            "mpm.elastic.friction_angle (30 deg)");
  m.residual_friction_deg = 25.0;
  EXPECT_EQ(error_of(m), "");
  m.friction_deg = 0.0;
  m.residual_friction_deg = 0.0;
  EXPECT_EQ(error_of(m),
            "mpm.elastic.softening_strain = 0.05: needs mpm.elastic.friction_angle > 0");
}

// A dilatancy cut-off stops a dilatancy: it needs one (job rule: mpm.elastic.dilatancy_cutoff).
TEST(ElasticMaterial, CutoffNeedsADilatancy) {
  farm::ElasticMaterial m = material();
  m.friction_deg = 40.0;
  m.dilatancy_cutoff = 0.1;
  EXPECT_EQ(error_of(m),
            "mpm.elastic.dilatancy_cutoff = 0.1: needs mpm.elastic.dilatancy_angle > 0");
  m.dilatancy_deg = 10.0;
  EXPECT_EQ(error_of(m), "");
  m.dilatancy_cutoff = -0.1;
  EXPECT_EQ(error_of(m), "mpm.elastic.dilatancy_cutoff = -0.1: must be >= 0");
}

// The one conversion is the expression the app used before the table (deg * M_PI / 180.0), so that
// a job's results stay bit for bit.
TEST(ElasticMaterial, RadiansAreTheJobsExpression) {
  for (const double deg : {0.0, 11.7, 27.5, 30.0, 38.3, 40.0, 89.999}) {
    EXPECT_EQ(farm::to_radians(deg), deg * M_PI / 180.0) << deg;
  }
  farm::ElasticMaterial m = material();
  m.friction_deg = 40.0;
  m.dilatancy_deg = 10.0;
  m.residual_friction_deg = 30.0;
  const farm::ElasticAngles a = farm::to_radians(m);
  EXPECT_EQ(a.friction, 40.0 * M_PI / 180.0);
  EXPECT_EQ(a.dilatancy, 10.0 * M_PI / 180.0);
  EXPECT_EQ(a.residual_friction, 30.0 * M_PI / 180.0);
}

// The radians of any degrees come back exactly through degrees_of_radians (the states the app
// wrote), a job's decimal as written; other radians get the nearest degrees.
TEST(ElasticMaterial, DegreesOfRadiansGiveTheRadiansBack) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any_angle(0.0, 90.0);
  for (int k = 0; k < 100000; ++k) {
    const double deg = k < 9000 ? 0.01 * k : any_angle(rng);
    const double rad = farm::to_radians(deg);
    const double back = farm::degrees_of_radians(rad);
    ASSERT_EQ(farm::to_radians(back), rad) << deg;
    EXPECT_NEAR(back, deg, 1e-12 * deg) << deg;
  }
  // The job's decimal comes back where another double has the same radians (11.7 and
  // 11.699999999999998 do).
  ASSERT_EQ(farm::to_radians(11.699999999999998), farm::to_radians(11.7));
  for (const double deg : {11.7, 27.5, 35.0, 38.3, 40.0, 0.1, 89.9}) {
    EXPECT_EQ(farm::degrees_of_radians(farm::to_radians(deg)), deg);
  }
  EXPECT_EQ(farm::degrees_of_radians(0.0), 0.0);
  EXPECT_NEAR(farm::degrees_of_radians(0.6), 0.6 * 180.0 / M_PI, 1e-12);
}
