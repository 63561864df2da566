// Stationary alignment (--align): the classic results of a static alignment on the same error
// model (Titterton & Weston ch. 10; Groves ch. 5): levelling leaves a tilt of b/g from an
// accelerometer bias b, and that tilt cancels the bias's position error afterwards;
// gyrocompassing leaves a heading error of eps_E / (Omega cos L) from the east gyro's bias.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "imunoise/nav/navigation.hpp"

namespace imunoise::nav {
namespace {

NavOptions stationary(double align_s) {
  NavOptions o;
  o.duration_s = 3600.0;
  o.step_s = 600.0;
  o.models = {Model::covariance};
  o.latitude_rad = 45.0 * std::numbers::pi / 180.0;
  o.align_s = align_s;
  return o;
}

TEST(NavAlign, LevellingTiltIsTheAccelerometerBiasOverGAndCancelsIt) {
  NavOptions o = stationary(600.0);
  const double b = 1e-3 * o.earth.gravity_m_s2;
  o.accel_axes[1].bias_m_s2 = b;  // east accelerometer: tilt about north, east channel
  const NavResult aligned = navigation_error(o);
  ASSERT_TRUE(aligned.alignment_rad.has_value());
  EXPECT_NEAR((*aligned.alignment_rad)[0] / (b / o.earth.gravity_m_s2), 1.0, 0.01);
  o.align_s = 0.0;
  const NavResult perfect = navigation_error(o);
  EXPECT_FALSE(perfect.alignment_rad.has_value());
  EXPECT_GT(perfect.models[0].east_m.back(), 1000.0);
  EXPECT_LT(aligned.models[0].east_m.back(), 1e-3 * perfect.models[0].east_m.back());
}

TEST(NavAlign, GyrocompassingHeadingIsTheEastDriftOverTheEarthRate) {
  NavOptions o = stationary(1800.0);
  const double c = 0.01 * std::numbers::pi / 180.0 / 3600.0;  // 0.01 deg/h
  o.axes[1].bias_rad_s = c;
  const NavResult r = navigation_error(o);
  const double expected = c / (o.earth.rotation_rad_s * std::cos(o.latitude_rad));
  EXPECT_NEAR((*r.alignment_rad)[2] / expected, 1.0, 0.01);
}

TEST(NavAlign, RefusesAnAbsurdTime) {
  NavOptions o = stationary(-1.0);
  o.axes[1].bias_rad_s = 1e-6;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("--align"), std::string::npos) << why;
}

}  // namespace
}  // namespace imunoise::nav
