// Tests of app/units: "<number> <unit>" strings in job files.
#include "app/job/units.hpp"

#include <gtest/gtest.h>

#include <numbers>

using app::parse_quantity;
using app::Quantity;

TEST(Units, ConvertsToTheCanonicalUnit) {
  std::string why;
  EXPECT_DOUBLE_EQ(*parse_quantity("100 kPa", Quantity::Pressure, why), 1e5);
  EXPECT_DOUBLE_EQ(*parse_quantity("  0.3 GPa ", Quantity::Pressure, why), 3e8);
  EXPECT_DOUBLE_EQ(*parse_quantity("130 um", Quantity::Length, why), 130e-6);
  EXPECT_DOUBLE_EQ(*parse_quantity("1.5 mm/s", Quantity::Velocity, why), 1.5e-3);
  EXPECT_DOUBLE_EQ(*parse_quantity("30 min", Quantity::Time, why), 1800.0);
  EXPECT_NEAR(*parse_quantity("0.5 rad", Quantity::Angle, why), 0.5 * 180.0 / std::numbers::pi,
              1e-12);
  EXPECT_DOUBLE_EQ(*parse_quantity("2.65 g/cm^3", Quantity::Density, why), 2650.0);
}

TEST(Units, WrongUnitNamesTheQuantityAndTheAcceptedUnits) {
  std::string why;
  EXPECT_FALSE(parse_quantity("100 m", Quantity::Pressure, why));
  EXPECT_EQ(why, "unit 'm' is not a pressure; use Pa, kPa, MPa, GPa");
  EXPECT_FALSE(parse_quantity("100 furlongs", Quantity::Length, why));
  EXPECT_EQ(why, "unknown unit 'furlongs'; use m, cm, mm, um");
  EXPECT_FALSE(parse_quantity("100", Quantity::Pressure, why));
  EXPECT_NE(why.find("needs a unit"), std::string::npos);
  EXPECT_FALSE(parse_quantity("kPa", Quantity::Pressure, why));
  EXPECT_NE(why.find("must be a number"), std::string::npos);
  EXPECT_FALSE(parse_quantity("3 kPa", Quantity::Dimensionless, why));
  EXPECT_NE(why.find("dimensionless"), std::string::npos);
  EXPECT_FALSE(parse_quantity("inf Pa", Quantity::Pressure, why));
}
