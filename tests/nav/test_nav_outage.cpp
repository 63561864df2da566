// GNSS outages: the error growth from an aided start against the single-channel closed forms
// (Earth rate off, where the covariance model must equal them): an initial position error
// stays, an initial velocity error v0 gives v0 sin(w0 t)/w0, an initial tilt phi0 gives
// R phi0 (1 - cos w0 t), an accelerometer bias the Schuler oscillation; the short-outage
// approximations of the textbooks (a gyro drift: g c t^3/6, Titterton & Weston ch. 12); and the
// error budget, whose shares sum to 1 and name the term that dominates.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "imunoise/error.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/outage.hpp"
#include "imunoise/nav/schuler.hpp"

namespace imunoise::nav {
namespace {

Coefficient present(double v) {
  Coefficient c;
  c.value = v;
  c.identified = true;
  return c;
}

NavOptions outage(std::vector<double> horizons) {
  NavOptions o;
  o.duration_s = 600.0;
  o.step_s = 600.0;
  o.models = {Model::covariance};
  o.earth_rate = false;
  o.latitude_rad = 45.0 * std::numbers::pi / 180.0;
  o.outage_s = std::move(horizons);
  return o;
}

double w0_of(const NavOptions& o) { return schuler::frequency_rad_s(o.earth.gravity_m_s2, o.earth.radius_m); }

TEST(NavOutage, InitialErrorsFollowTheSchulerLoop) {
  NavOptions o = outage({10, 60, 300});
  o.initial_pos_m = 2.0;
  const auto pos = outage_errors(o, {}, {});
  for (const auto& p : pos) {
    EXPECT_NEAR(p.north_m, 2.0, 1e-9);
    EXPECT_NEAR(p.horizontal_m, 2.0 * std::numbers::sqrt2, 1e-9);
  }
  o.initial_pos_m = 0.0;
  o.initial_vel_m_s = 0.1;
  const double w0 = w0_of(o);
  for (const auto& p : outage_errors(o, {}, {})) {
    EXPECT_NEAR(p.north_m / (0.1 * std::sin(w0 * p.t_s) / w0), 1.0, 1e-9) << p.t_s;
    EXPECT_NEAR(p.velocity_m_s / (0.1 * std::numbers::sqrt2 * std::cos(w0 * p.t_s)), 1.0, 1e-9) << p.t_s;
  }
  o.initial_vel_m_s = 0.0;
  o.initial_att_rad = 1e-3;
  for (const auto& p : outage_errors(o, {}, {})) {
    const double expected = o.earth.radius_m * 1e-3 * (1 - std::cos(w0 * p.t_s));
    EXPECT_NEAR(p.north_m / expected, 1.0, 1e-9) << p.t_s;
    // Short outage: g phi0 t^2 / 2.
    if (p.t_s <= 60) EXPECT_NEAR(p.north_m / (0.5 * o.earth.gravity_m_s2 * 1e-3 * p.t_s * p.t_s), 1.0, 1e-3);
  }
}

TEST(NavOutage, SensorTermsMatchTheClosedFormsAndTheShortOutageLimits) {
  NavOptions o = outage({10, 30, 60, 300});
  const double w0 = w0_of(o), r = o.earth.radius_m, g = o.earth.gravity_m_s2;
  std::array<AccelTerms, 3> accel{};
  accel[0].bias_m_s2 = 1e-3 * g;
  for (const auto& p : outage_errors(o, {}, accel)) {
    EXPECT_NEAR(p.north_m / (r * schuler::accel_bias_rad(accel[0].bias_m_s2, p.t_s, w0, r)), 1.0, 1e-9);
    EXPECT_NEAR(p.east_m, 0.0, 1e-12);  // the east accelerometer has no bias
    if (p.t_s <= 60) EXPECT_NEAR(p.north_m / (0.5 * 1e-3 * g * p.t_s * p.t_s), 1.0, 1e-3) << p.t_s;
  }
  std::array<GyroTerms, 3> gyro{};
  gyro[1].bias_rad_s = 1e-5;  // east gyro: north channel
  for (const auto& p : outage_errors(o, gyro, {})) {
    EXPECT_NEAR(p.north_m / (r * schuler::constant_drift_rad(1e-5, p.t_s, w0)), 1.0, 1e-9);
    if (p.t_s <= 60) EXPECT_NEAR(p.north_m / (g * 1e-5 * std::pow(p.t_s, 3) / 6.0), 1.0, 1e-3) << p.t_s;
  }
}

TEST(NavOutage, BudgetSharesSumToOneAndNameTheDominantTerm) {
  NavOptions o = outage({10, 300});
  o.initial_pos_m = 1.0;
  o.initial_att_rad = 1e-4;
  std::array<GyroTerms, 3> gyro{};
  for (auto& t : gyro) t.n_rad_sqrt_s = 1e-5;
  std::array<AccelTerms, 3> accel{};
  for (auto& t : accel) t.bias_m_s2 = 5e-3;
  const auto points = outage_errors(o, gyro, accel);
  for (const auto& p : points) {
    double sum = 0.0;
    for (const auto& [term, share] : p.budget) sum += share;
    EXPECT_NEAR(sum, 1.0, 1e-12) << p.t_s;
    EXPECT_NEAR(p.horizontal_m, std::hypot(p.north_m, p.east_m), 1e-9);
    for (std::size_t i = 1; i < p.budget.size(); ++i) EXPECT_GE(p.budget[i - 1].second, p.budget[i].second);
  }
  // 10 s: the 1 m start (1 m^2 a channel) beats 5 mg of bias (0.25 m); 300 s: the bias (~2.2 km).
  EXPECT_EQ(points[0].budget.front().first, "initial position");
  EXPECT_EQ(points[1].budget.front().first, "accel bias");
  // The shares are the variances' own: the bias alone gives its share of the total.
  std::array<AccelTerms, 3> bias_only = accel;
  const auto alone = outage_errors(outage({300}), {}, bias_only);
  double share = 0.0;
  for (const auto& [term, s] : points[1].budget) {
    if (term == "accel bias") share = s;
  }
  EXPECT_NEAR(share, std::pow(alone[0].horizontal_m / points[1].horizontal_m, 2), 1e-9);
}

// The covariance model's budget at every reported time: shares that add up to 1, each the
// variance of its term alone over the whole (with the Earth rate on: the coupling is linear too).
TEST(NavBudget, CovarianceSharesAreEachTermAloneOverTheWhole) {
  NavOptions o;
  o.duration_s = 3600.0;
  o.step_s = 600.0;
  o.models = {Model::covariance};
  o.latitude_rad = 45.0 * std::numbers::pi / 180.0;
  for (auto& a : o.axes) {
    a.coefficients.random_walk = present(1e-5);
    a.coefficients.bias_instability = present(5e-6);
  }
  for (auto& a : o.accel_axes) a.bias_m_s2 = 2e-3;
  const NavResult whole = navigation_error(o);
  const ModelSeries& c = whole.models[0];
  ASSERT_EQ(c.budget.size(), 3u);  // gyro N, gyro B, accel bias
  for (std::size_t i = 1; i < c.t_s.size(); ++i) {
    double sum = 0.0;
    for (const auto& [term, shares] : c.budget) sum += shares[i];
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  NavOptions alone = o;
  for (auto& a : alone.axes) a = GyroAxisNoise{};
  const NavResult bias = navigation_error(alone);
  const double r2 = std::pow(bias.models[0].radial_m.back() / c.radial_m.back(), 2);
  EXPECT_EQ(c.budget[2].first, "accel bias");
  EXPECT_NEAR(c.budget[2].second.back(), r2, 1e-9);
}

// What the answer cannot support is said: a gyro-only outage, a horizon beyond the record.
TEST(NavOutage, NotesSayWhatTheAnswerLeavesOut) {
  NavOptions o = outage({10, 1200});
  o.axes[1].coefficients.random_walk = present(1e-5);
  o.measured_s = 900.0;
  const NavResult r = navigation_error(o);
  auto said = [&](const std::string& text) {
    for (const auto& n : r.notes) {
      if (n.find(text) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(said("the outage errors are the gyros' alone"));
  EXPECT_TRUE(said("measured on 900 s of record and the navigation error runs to 1200 s"));
  o.measured_s = 7200.0;
  o.accel_axes[0].bias_m_s2 = 1e-3;
  for (const auto& n : navigation_error(o).notes) {
    EXPECT_EQ(n.find("extrapolated"), std::string::npos) << n;
    EXPECT_EQ(n.find("gyros' alone"), std::string::npos) << n;
  }
}

TEST(NavOutage, BadHorizonsAreRefused) {
  NavOptions o = outage({0.5});
  EXPECT_THROW(outage_errors(o, {}, {}), InputError);
  o.outage_s = {-10};
  EXPECT_THROW(outage_errors(o, {}, {}), InputError);
}

TEST(NavOutageCli, JsonListsEachHorizonWithItsBudget) {
  const auto run = test::run_cli({"nav", "--N", "1e-3", "--accel-bias", "1", "--accel-units", "mg", "--outage",
                                  "10,30,60,300", "--initial-pos-m", "0.5", "--format", "json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  ASSERT_EQ(doc["outage"].size(), 4u);
  const auto& last = doc["outage"][3];
  EXPECT_EQ(last["t_s"], 300.0);
  for (const char* key : {"north_m", "east_m", "horizontal_m", "velocity_m_s", "attitude_deg"}) {
    EXPECT_TRUE(last[key].is_number()) << key;
  }
  double sum = 0.0;
  for (const auto& [term, share] : last["budget"].items()) sum += share.get<double>();
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_TRUE(last["budget"].contains("accel bias"));
  const auto bad = test::run_cli({"nav", "--N", "1e-3", "--outage", "10,0.5"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--outage 0.5 s"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace imunoise::nav
