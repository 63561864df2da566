// Units: parsing, SI factors checked against their definitions, integral/derivative naming.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "imunoise/units.hpp"
#include "io_test_support.hpp"

namespace imunoise {
namespace {

// Reference factors written out from the definitions, independently of units.hpp's constants.
constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180.0;

struct Expected {
  const char* text;
  const char* canonical;
  Quantity quantity;
  double to_si;
};

class ParseUnit : public ::testing::TestWithParam<Expected> {};

TEST_P(ParseUnit, NameQuantityAndFactor) {
  const Expected& e = GetParam();
  const Unit unit = parse_unit(e.text);
  EXPECT_EQ(unit.name, e.canonical);
  EXPECT_EQ(unit.quantity, e.quantity);
  EXPECT_DOUBLE_EQ(unit.to_si, e.to_si) << e.text;
}

INSTANTIATE_TEST_SUITE_P(
    KnownUnits, ParseUnit,
    ::testing::Values(
        Expected{"rad/s", "rad/s", Quantity::angular_rate, 1.0},
        Expected{"deg/s", "deg/s", Quantity::angular_rate, deg},
        Expected{"dps", "deg/s", Quantity::angular_rate, deg},
        Expected{"deg/h", "deg/h", Quantity::angular_rate, deg / 3600.0},
        Expected{"dph", "deg/h", Quantity::angular_rate, deg / 3600.0},
        Expected{"rad/h", "rad/h", Quantity::angular_rate, 1.0 / 3600.0},
        Expected{"mrad/s", "mrad/s", Quantity::angular_rate, 0.001},
        Expected{"mdeg/s", "mdeg/s", Quantity::angular_rate, deg / 1000.0},
        Expected{"arcsec/s", "arcsec/s", Quantity::angular_rate, deg / 3600.0},
        Expected{"deg/min", "deg/min", Quantity::angular_rate, deg / 60.0},
        Expected{"rpm", "rpm", Quantity::angular_rate, 2.0 * pi / 60.0},
        Expected{"rad", "rad", Quantity::angle, 1.0},
        Expected{"deg", "deg", Quantity::angle, deg},
        Expected{"mrad", "mrad", Quantity::angle, 0.001},
        Expected{"arcsec", "arcsec", Quantity::angle, deg / 3600.0},
        Expected{"arcmin", "arcmin", Quantity::angle, deg / 60.0},
        Expected{"m/s^2", "m/s^2", Quantity::acceleration, 1.0},
        Expected{"m/s2", "m/s^2", Quantity::acceleration, 1.0},
        Expected{"g", "g", Quantity::acceleration, 9.80665},
        Expected{"mg", "mg", Quantity::acceleration, 9.80665e-3},
        Expected{"ug", "ug", Quantity::acceleration, 9.80665e-6},
        Expected{"\xC2\xB5g", "ug", Quantity::acceleration, 9.80665e-6},  // micro sign
        Expected{"ft/s^2", "ft/s^2", Quantity::acceleration, 0.3048},
        Expected{"m/s", "m/s", Quantity::velocity, 1.0},
        Expected{"1", "1", Quantity::dimensionless, 1.0},
        Expected{"", "1", Quantity::dimensionless, 1.0},
        Expected{"ff", "1", Quantity::dimensionless, 1.0},
        Expected{"s", "s", Quantity::time, 1.0},
        Expected{"ns", "ns", Quantity::time, 1e-9},
        Expected{"us", "us", Quantity::time, 1e-6},
        Expected{"V", "V", Quantity::voltage, 1.0},
        Expected{"mV", "mV", Quantity::voltage, 1e-3},
        Expected{"  deg/s ", "deg/s", Quantity::angular_rate, deg}));

TEST(Units, UnknownUnitListsTheKnownOnes) {
  const std::string message = test::expect_input_error(
      [] { parse_unit("furlong/fortnight"); }, {"'furlong/fortnight'", "deg/s", "m/s^2", "rpm"});
  EXPECT_NE(message.find("dps"), std::string::npos) << "aliases are listed too";
}

TEST(Units, NamesAreCaseSensitive) {
  // "MV" would be megavolt, "G" could be gauss: guessing would be worse than refusing.
  test::expect_input_error([] { parse_unit("DEG/S"); }, {"DEG/S"});
  test::expect_input_error([] { parse_unit("MV"); }, {"MV"});
}

TEST(Units, EveryListedNameParsesToItself) {
  const auto names = known_unit_names();
  EXPECT_GE(names.size(), 25u);
  for (const auto& name : names) EXPECT_EQ(parse_unit(name).name, name);
}

TEST(Units, ToAndFromSi) {
  const Unit deg_h = parse_unit("deg/h");
  EXPECT_DOUBLE_EQ(to_si(3600.0, deg_h), deg);
  EXPECT_DOUBLE_EQ(from_si(deg, deg_h), 3600.0);
  EXPECT_EQ(si_unit_name(Quantity::acceleration), "m/s^2");
  EXPECT_EQ(quantity_name(Quantity::angular_rate), "angular rate");
}

TEST(Units, IntegralAndDerivativeNames) {
  const std::pair<const char*, const char*> rate_to_angle[] = {
      {"deg/s", "deg"},   {"rad/s", "rad"},     {"mrad/s", "mrad"}, {"arcsec/s", "arcsec"},
      {"m/s^2", "m/s"},   {"ft/s^2", "ft/s"},   {"1", "s"},         {"deg/h", "deg/h*s"},
      {"g", "g*s"},       {"rpm", "rpm*s"},     {"mg", "mg*s"},     {"deg/min", "deg/min*s"}};
  for (const auto& [rate, angle] : rate_to_angle) {
    const Unit rate_unit = parse_unit(rate);
    const Unit integral = integral_unit(rate_unit);
    EXPECT_EQ(integral.name, angle) << rate;
    // Integrating over seconds (SI) never changes the factor.
    EXPECT_EQ(integral.to_si, rate_unit.to_si) << rate;
    const Unit back = derivative_unit(integral);
    EXPECT_EQ(back.name, rate_unit.name) << rate;
    EXPECT_EQ(back.quantity, rate_unit.quantity) << rate;
    EXPECT_EQ(back.to_si, rate_unit.to_si) << rate;
  }
  EXPECT_EQ(integral_unit(parse_unit("deg/s")).quantity, Quantity::angle);
  EXPECT_EQ(integral_unit(parse_unit("m/s^2")).quantity, Quantity::velocity);
  EXPECT_EQ(integral_unit(parse_unit("ff")).quantity, Quantity::time);
  EXPECT_EQ(derivative_unit(parse_unit("deg")).name, "deg/s");
  EXPECT_EQ(derivative_unit(parse_unit("m/s")).name, "m/s^2");
  EXPECT_EQ(derivative_unit(parse_unit("s")).name, "1");
  EXPECT_EQ(derivative_unit(parse_unit("arcmin")).name, "arcmin/s");
  const Unit ns_per_s = derivative_unit(parse_unit("ns"));
  EXPECT_EQ(ns_per_s.name, "ns/s");
  EXPECT_EQ(ns_per_s.quantity, Quantity::dimensionless);
  EXPECT_EQ(ns_per_s.to_si, 1e-9);
  // The derived spellings parse back.
  EXPECT_EQ(parse_unit("deg/h*s").to_si, parse_unit("deg/h").to_si);
  EXPECT_EQ(parse_unit("g*s").quantity, Quantity::velocity);
}

TEST(Units, IntegralOfANonRateIsAnError) {
  test::expect_input_error([] { integral_unit(parse_unit("deg")); }, {"'deg'", "angle"});
  test::expect_input_error([] { integral_unit(parse_unit("m/s")); }, {"'m/s'", "velocity"});
  test::expect_input_error([] { integral_unit(parse_unit("V")); }, {"'V'", "voltage"});
  test::expect_input_error([] { derivative_unit(parse_unit("deg/s")); }, {"'deg/s'"});
  test::expect_input_error([] { derivative_unit(parse_unit("1")); }, {"'1'"});
}

TEST(Units, CustomaryNoiseUnitsFromFirstPrinciples) {
  // Each factor rebuilt from 1 h = 3600 s, so sqrt(h) = sqrt(3600) sqrt(s).
  const double sqrt_h = std::sqrt(3600.0);
  EXPECT_DOUBLE_EQ(units::deg_per_sqrt_h_to_rad_per_sqrt_s, deg / sqrt_h);
  EXPECT_DOUBLE_EQ(units::deg_per_h_to_rad_per_s, deg / 3600.0);
  EXPECT_DOUBLE_EQ(units::deg_per_h_per_sqrt_h_to_rad_per_s_per_sqrt_s, deg / 3600.0 / sqrt_h);
  EXPECT_DOUBLE_EQ(units::deg_per_h2_to_rad_per_s2, deg / (3600.0 * 3600.0));
  EXPECT_DOUBLE_EQ(units::arcsec_to_rad, deg / 3600.0);
  // Published value: 1 deg/h = 4.84813681109536e-6 rad/s (= 1 arcsec/s).
  EXPECT_NEAR(units::deg_per_h_to_rad_per_s, 4.84813681109536e-6, 1e-19);
  EXPECT_EQ(customary_gyro_N.name, "deg/sqrt(h)");
  EXPECT_EQ(customary_gyro_K.si_name, "rad/s/sqrt(s)");
  EXPECT_EQ(customary_gyro_R.to_si, units::deg_per_h2_to_rad_per_s2);
  EXPECT_EQ(customary_gyro_Q.name, "arcsec");
  EXPECT_EQ(customary_gyro_B.name, "deg/h");
  // A typical tactical gyro: N = 0.05 deg/sqrt(h) is 0.05/60 deg/sqrt(s).
  EXPECT_DOUBLE_EQ(0.05 * customary_gyro_N.to_si / deg, 0.05 / 60.0);
}

}  // namespace
}  // namespace imunoise
