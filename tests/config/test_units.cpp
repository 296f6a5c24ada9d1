#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "config/units.hpp"

namespace snapjump::units {
namespace {

class UnitsTest : public ::testing::Test {
 protected:
  UnitParser parser;
};

TEST_F(UnitsTest, LengthsWithAndWithoutSpaceAndPrefix) {
  EXPECT_DOUBLE_EQ(parser.parse("30 mm", Dimension::Length), 0.030);
  EXPECT_DOUBLE_EQ(parser.parse("30mm", Dimension::Length), 0.030);
  EXPECT_DOUBLE_EQ(parser.parse("  2.5 cm ", Dimension::Length), 0.025);
  EXPECT_DOUBLE_EQ(parser.parse("1.5e-3 m", Dimension::Length), 1.5e-3);
  EXPECT_NEAR(parser.parse("250 um", Dimension::Length), 250e-6, 1e-18);
}

TEST_F(UnitsTest, BareNumberIsSI) {
  EXPECT_DOUBLE_EQ(parser.parse("0.03", Dimension::Length), 0.03);
  EXPECT_DOUBLE_EQ(parser.parse("+1200000", Dimension::Pressure), 1.2e6);
}

TEST_F(UnitsTest, PressuresForcesMasses) {
  EXPECT_DOUBLE_EQ(parser.parse("1.2 MPa", Dimension::Pressure), 1.2e6);
  EXPECT_DOUBLE_EQ(parser.parse("3 kPa", Dimension::Pressure), 3000.0);
  EXPECT_NEAR(parser.parse("1 bar", Dimension::Pressure), 1e5, 1e-9);
  EXPECT_DOUBLE_EQ(parser.parse("0.48 N", Dimension::Force), 0.48);
  EXPECT_DOUBLE_EQ(parser.parse("480 mN", Dimension::Force), 0.48);
  EXPECT_DOUBLE_EQ(parser.parse("49 g", Dimension::Mass), 0.049);
}

TEST_F(UnitsTest, AnglesInDegrees) {
  EXPECT_NEAR(parser.parse("80 deg", Dimension::Angle), 80.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_NEAR(parser.parse("90 degree", Dimension::Angle), std::numbers::pi / 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(parser.parse("1.2 rad", Dimension::Angle), 1.2);
}

TEST_F(UnitsTest, CompoundUnits) {
  EXPECT_NEAR(parser.parse("1160 kg/m^3", Dimension::Density), 1160.0, 1e-9);
  EXPECT_NEAR(parser.parse("1.16 g/cm^3", Dimension::Density), 1160.0, 1e-9);
  EXPECT_NEAR(parser.parse("200 mL", Dimension::Volume), 200e-6, 1e-18);
  EXPECT_NEAR(parser.parse("0.2 L", Dimension::Volume), 200e-6, 1e-18);
  EXPECT_NEAR(parser.parse("1.0e-3 Pa^-1 s^-2", Dimension::ValveAcceleration), 1.0e-3, 1e-18);
  EXPECT_NEAR(parser.parse("1 kPa^-1 s^-2", Dimension::ValveAcceleration), 1.0e-3, 1e-18);
  EXPECT_NEAR(parser.parse("5.0e-5 Pa^-1 s^-1", Dimension::ValveRate), 5.0e-5, 1e-18);
  EXPECT_NEAR(parser.parse("10 ms", Dimension::Time), 0.01, 1e-15);
}

TEST_F(UnitsTest, DimensionlessTakesNoUnit) {
  EXPECT_DOUBLE_EQ(parser.parse("0.45", Dimension::Dimensionless), 0.45);
  try {
    (void)parser.parse("0.45 mm", Dimension::Dimensionless);
    FAIL() << "a unit on a dimensionless number must be rejected";
  } catch (const UnitError& e) {
    EXPECT_NE(std::string(e.what()).find("plain number"), std::string::npos) << e.what();
  }
}

void expect_error(const UnitParser& p, const std::string& text, Dimension d,
                  const std::string& fragment) {
  try {
    (void)p.parse(text, d);
    FAIL() << "'" << text << "' should be rejected";
  } catch (const UnitError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << fragment;
  }
}

TEST_F(UnitsTest, WrongDimensionNamesBoth) {
  expect_error(parser, "30 kg", Dimension::Length, "'kg' is a mass, but a length is needed");
  expect_error(parser, "1.2 N", Dimension::Pressure, "is a force, but a pressure is needed");
  expect_error(parser, "80 mm", Dimension::Angle, "is a length, but an angle is needed");
  expect_error(parser, "2 J", Dimension::Force, "is an energy");
}

TEST_F(UnitsTest, GarbageIsRejected) {
  expect_error(parser, "30 mmm", Dimension::Length, "unknown unit 'mmm'");
  expect_error(parser, "mm", Dimension::Length, "does not start with a number");
  expect_error(parser, "", Dimension::Length, "is empty");
  expect_error(parser, "nan mm", Dimension::Length, "not a finite number");
  expect_error(parser, "inf", Dimension::Length, "not a finite number");
  expect_error(parser, "1e999 m", Dimension::Length, "out of range");
}

TEST_F(UnitsTest, AReciprocalIsNotTheQuantity) {
  // UDUNITS converts m^-1 to m as 1/x: 0.5 m^-1 would read as 2 m.
  expect_error(parser, "0.5 m^-1", Dimension::Length,
               "'m^-1' is the reciprocal of a length, but a length is needed (in m");
  expect_error(parser, "30 mm^-1", Dimension::Length, "reciprocal of a length");
  expect_error(parser, "1 Pa^-1", Dimension::Pressure, "reciprocal of a pressure");
  expect_error(parser, "1 Hz", Dimension::Time, "'Hz' is the reciprocal of a time");
  expect_error(parser, "2 N^-1", Dimension::Force, "reciprocal of a force");
  expect_error(parser, "1 Pa s^2", Dimension::ValveAcceleration, "reciprocal of");
  expect_error(parser, "3 rad^-1", Dimension::Angle, "not an angle's unit");
  expect_error(parser, "3 deg^2", Dimension::Angle, "not an angle's unit");
  // The same quantity in other words is still taken.
  EXPECT_NEAR(parser.parse("1 m^3/m^2", Dimension::Length), 1.0, 1e-15);
  EXPECT_NEAR(parser.parse("2 1/(Pa s)", Dimension::ValveRate), 2.0, 1e-15);
  EXPECT_NEAR(parser.parse("1 g cm^-3", Dimension::Density), 1000.0, 1e-9);
  EXPECT_NEAR(parser.parse("1 N.m^-1", Dimension::Stiffness), 1.0, 1e-15);
}

TEST_F(UnitsTest, OnlyProductsAndSmallPowersOfUnits) {
  // UDUNITS reads '@' (and after, from, since, ref) as an offset: 30 mm @ 5 would be 35 mm.
  expect_error(parser, "30 mm @ 5", Dimension::Length, "shifts its origin with '@'");
  expect_error(parser, "30 mm from 5", Dimension::Length, "shifts its origin with 'from'");
  expect_error(parser, "30 mm After 5", Dimension::Length, "shifts its origin with 'After'");
  expect_error(parser, "10 s since 2000-01-01", Dimension::Time, "shifts its origin");
  expect_error(parser, "30 mm ref 5", Dimension::Length, "shifts its origin");
  expect_error(parser, "3 lg(re 1 Pa)", Dimension::Pressure, "is a logarithm");
  // A power too large for an int wraps around in the library (m^99999999999999999999 is m^-1).
  expect_error(parser, "30 mm^99999999999999999999", Dimension::Length,
               "has the power 99999999999999999999; a unit's powers are whole numbers from -4 "
               "to 4");
  expect_error(parser, "1 m^5/m^4", Dimension::Length, "has the power 5");
  expect_error(parser, "1 m-7 m^8", Dimension::Length, "has the power -7");
  expect_error(parser, "1 m^0", Dimension::Length, "has the power 0");
  // Numbers inside the unit are factors (and "m -2" is -2 m).
  expect_error(parser, "30 mm 2", Dimension::Length, "holds a number");
  expect_error(parser, "30 m -2", Dimension::Length, "holds a number");
  expect_error(parser, "30 m/2", Dimension::Length, "holds a number");
  expect_error(parser, "30 m^2.5/m^1", Dimension::Length, "holds a number");
  expect_error(parser, "30 m;", Dimension::Length, "holds ';'");
  // Products, quotients and powers in their usual spellings are taken.
  EXPECT_NEAR(parser.parse("1 kg/m**3", Dimension::Density), 1.0, 1e-15);
  EXPECT_NEAR(parser.parse("1 kg/m3", Dimension::Density), 1.0, 1e-15);
  EXPECT_NEAR(parser.parse("1 kg.m-3", Dimension::Density), 1.0, 1e-15);
  EXPECT_NEAR(parser.parse("1 kg/m\u00b3", Dimension::Density), 1.0, 1e-15);
  EXPECT_NEAR(parser.parse("1 kg/(m^2 m)", Dimension::Density), 1.0, 1e-15);
  EXPECT_NEAR(parser.parse("3 kN/m", Dimension::Stiffness), 3000.0, 1e-9);
  EXPECT_NEAR(parser.parse("5 \u00b5m", Dimension::Length), 5e-6, 1e-20);
}

TEST_F(UnitsTest, ABareNumberIsOneWithoutAUnit) {
  EXPECT_TRUE(is_bare_number("40"));
  EXPECT_TRUE(is_bare_number(" 4e-2 "));
  EXPECT_TRUE(is_bare_number("+3"));
  EXPECT_FALSE(is_bare_number("40 mm"));
  EXPECT_FALSE(is_bare_number("40mm"));
  EXPECT_FALSE(is_bare_number("mm"));
  EXPECT_FALSE(is_bare_number(""));
  EXPECT_FALSE(is_bare_number("+"));
}

TEST_F(UnitsTest, UnitsOfAnyDimensionAreKnownAsUnits) {
  EXPECT_TRUE(parser.is_unit("mm"));
  EXPECT_TRUE(parser.is_unit(" kPa "));
  EXPECT_TRUE(parser.is_unit("kg/m^3"));
  EXPECT_TRUE(parser.is_unit("N"));
  EXPECT_FALSE(parser.is_unit("mmm"));
  EXPECT_FALSE(parser.is_unit("examples/default.toml"));
  EXPECT_FALSE(parser.is_unit(""));
}

TEST_F(UnitsTest, FromSiInvertsToSi) {
  EXPECT_NEAR(parser.from_si(0.03, "mm", Dimension::Length), 30.0, 1e-12);
  EXPECT_NEAR(parser.from_si(1.2e6, "MPa", Dimension::Pressure), 1.2, 1e-12);
}

}  // namespace
}  // namespace snapjump::units
