// plan_navigation: a request in the user's units becomes SI NavOptions; the checks name the
// option as the edge spells it.
#include <gtest/gtest.h>

#include <limits>
#include <numbers>
#include <string>

#include "imunoise/error.hpp"
#include "imunoise/nav/request.hpp"

namespace imunoise::nav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string error_of(const NavRequest& r) {
  try {
    plan_navigation(r);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(NavRequest, CoefficientsAndBiasInTheUsersUnitBecomeSi) {
  NavRequest r;
  r.coefficients.n = 8.9e-4;  // deg/sqrt(s)
  r.coefficients.k = 1.5e-5;  // deg/s/sqrt(s)
  r.coefficients_given = true;
  r.bias = 0.01;  // deg/s
  r.hours = 0.5;
  r.step_s = 7200.0;
  r.latitude_deg = 45.0;
  const NavOptions o = plan_navigation(r);
  for (const GyroAxisNoise& a : o.axes) {
    EXPECT_NEAR(a.coefficients.random_walk.value, 8.9e-4 * kDeg, 1e-18);
    EXPECT_NEAR(a.coefficients.rate_random_walk.value, 1.5e-5 * kDeg, 1e-18);
    EXPECT_NEAR(a.bias_rad_s, 0.01 * kDeg, 1e-18);
  }
  EXPECT_DOUBLE_EQ(o.duration_s, 1800.0);
  EXPECT_DOUBLE_EQ(o.step_s, 1800.0);  // clipped to the operating time
  EXPECT_DOUBLE_EQ(o.latitude_rad, 45.0 * kDeg);
}

TEST(NavRequest, FitsAreAllThreeOrNoneAndNeverBesideCoefficients) {
  GyroAxisNoise fitted;
  fitted.coefficients.random_walk.value = 1e-5;
  fitted.coefficients.random_walk.identified = true;
  NavRequest r;
  r.fitted_axes[0] = fitted;
  EXPECT_NE(error_of(r).find("all three axes (--from-x, --from-y and --from-z"), std::string::npos) << error_of(r);
  r.fitted_axes.fill(fitted);
  EXPECT_EQ(error_of(r), "");
  EXPECT_EQ(plan_navigation(r).axes[2].coefficients.random_walk.value, 1e-5);
  r.coefficients_given = true;
  EXPECT_NE(error_of(r).find("not both (--bias may be added"), std::string::npos);
  EXPECT_NE(error_of(r).find("coefficients (--Q --N --B --K --R, --gm-sigma --gm-tau) or as fits (--from or"),
            std::string::npos) << error_of(r);
}

TEST(NavRequest, MessagesNameTheOptionAsTheEdgeSpellsIt) {
  NavRequest r;
  r.hours = 0.0;
  EXPECT_NE(error_of(r).find("--hours must be positive"), std::string::npos);
  r.names = {"", '_'};
  EXPECT_EQ(error_of(r).rfind("hours must be positive", 0), 0U) << error_of(r);
  r.hours = 1.0;
  r.latitude_deg = 91.0;
  EXPECT_NE(error_of(r).find("latitude 91 is beyond +-90"), std::string::npos);
  r.latitude_deg = 0.0;
  r.units = "m/s^2";
  EXPECT_NE(error_of(r).find("units m/s^2 is not an angular rate"), std::string::npos);
  r.units = "deg/h";
  r.bias = std::numeric_limits<double>::infinity();
  EXPECT_NE(error_of(r).find("bias must be finite"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::nav
