// The accelerometers in the navigation error: the Schuler closed forms per accelerometer term
// against hand-computed values and against the covariance model (single channel, Earth rate
// off, where the two must agree to rounding); the Monte Carlo against the covariance by the
// statistical test of test_nav_montecarlo.cpp (|z| < 4 per channel and time, 300 runs); and the
// command line's --accel-* options.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "imunoise/error.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/nav/request.hpp"
#include "imunoise/nav/schuler.hpp"
#include "imunoise/units.hpp"

namespace imunoise::nav {
namespace {

constexpr double kMg = 1e-3 * units::g_to_m_per_s2;

Coefficient present(double v) {
  Coefficient c;
  c.value = v;
  c.identified = true;
  return c;
}

NavOptions accel_only(double hours = 2.0) {
  NavOptions o;
  o.duration_s = hours * 3600.0;
  o.step_s = 300.0;
  o.latitude_rad = 58.5 * std::numbers::pi / 180.0;
  return o;
}

TEST(NavAccelSchuler, BiasIsTheBoundedSchulerOscillation) {
  // x = b/w0^2 (1 - cos w0 t): at half a Schuler period the peak 2 b / w0^2 = 2 R b / g, and back
  // to zero after a whole period. 1 mg with R = 6380 km: 2 x 6380 km x 1e-3 = 12.76 km.
  const EarthModel e;
  const double w0 = schuler::frequency_rad_s(e.gravity_m_s2, e.radius_m);
  const double b = 1e-3 * e.gravity_m_s2;
  EXPECT_NEAR(e.radius_m * schuler::accel_bias_rad(b, std::numbers::pi / w0, w0, e.radius_m), 12760.0, 1e-6);
  EXPECT_NEAR(e.radius_m * schuler::accel_bias_rad(b, 2 * std::numbers::pi / w0, w0, e.radius_m), 0.0, 1e-6);
  // Small t: x = b t^2 / 2 (1 - (w0 t)^2 / 12 + ...), the free fall of an uncorrected bias.
  const double x = w0 * 10.0;
  EXPECT_NEAR(e.radius_m * schuler::accel_bias_rad(b, 10.0, w0, e.radius_m) / (0.5 * b * 100.0), 1.0 - x * x / 12.0,
              1e-10);
}

TEST(NavAccelSchuler, WhiteAndRandomWalkAgainstTheirIntegrals) {
  // VRW N: var x = N^2 int_0^t sin^2(w0 u)/w0^2 du; random walk K: var x = K^2 int_0^t
  // ((1 - cos w0 u)/w0^2)^2 du. Both integrals by the midpoint rule, 2e5 steps.
  const EarthModel e;
  const double w0 = schuler::frequency_rad_s(e.gravity_m_s2, e.radius_m);
  const double t = 5000.0, n = 3e-4, k = 2e-5;
  double iw = 0.0, ik = 0.0;
  const int steps = 200000;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) * t / steps;
    iw += std::pow(std::sin(w0 * u) / w0, 2) * t / steps;
    ik += std::pow((1 - std::cos(w0 * u)) / (w0 * w0), 2) * t / steps;
  }
  EXPECT_NEAR(e.radius_m * schuler::accel_white_rad(n, t, w0, e.radius_m) / (n * std::sqrt(iw)), 1.0, 1e-8);
  EXPECT_NEAR(e.radius_m * schuler::accel_random_walk_rad(k, t, w0, e.radius_m) / (k * std::sqrt(ik)), 1.0, 1e-8);
}

// Relative to the largest error of the series: a bias's Schuler oscillation returns to zero
// every period, where a ratio would only measure rounding.
void expect_covariance_equals_schuler(NavOptions o, double tol) {
  o.models = {Model::schuler, Model::covariance};
  o.earth_rate = false;
  const NavResult r = navigation_error(o);
  const ModelSeries& s = r.models[0];
  const ModelSeries& c = r.models[1];
  const double scale_n = *std::max_element(s.north_m.begin(), s.north_m.end());
  const double scale_e = *std::max_element(s.east_m.begin(), s.east_m.end());
  double worst = 0.0;
  for (std::size_t i = 1; i < s.t_s.size(); ++i) {
    const double dn = std::abs(c.north_m[i] - s.north_m[i]) / scale_n;
    const double de = std::abs(c.east_m[i] - s.east_m[i]) / scale_e;
    worst = std::max({worst, dn, de});
    EXPECT_LT(dn, tol) << "north at t = " << s.t_s[i];
    EXPECT_LT(de, tol) << "east at t = " << s.t_s[i];
  }
  std::printf("accelerometer covariance vs closed form: worst relative difference %.3g\n", worst);
}

TEST(NavAccelCovariance, EqualsClosedFormPerTerm) {
  struct Case {
    const char* name;
    void (*set)(AccelAxisNoise&);
  };
  const Case cases[] = {
      {"bias", [](AccelAxisNoise& a) { a.bias_m_s2 = 1.0 * kMg; }},
      {"ramp", [](AccelAxisNoise& a) { a.coefficients.rate_ramp = present(1e-7); }},
      {"N", [](AccelAxisNoise& a) { a.coefficients.random_walk = present(5e-4); }},
      {"K", [](AccelAxisNoise& a) { a.coefficients.rate_random_walk = present(3e-6); }},
      {"B", [](AccelAxisNoise& a) { a.coefficients.bias_instability = present(0.05 * kMg); }},
      {"Q", [](AccelAxisNoise& a) { a.coefficients.quantization = present(1e-3); }},
      {"GM", [](AccelAxisNoise& a) {
         GaussMarkovTerm gm;
         gm.sigma = present(0.1 * kMg);
         gm.correlation_time_s = present(200.0);
         a.coefficients.gauss_markov = {gm};
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    NavOptions o = accel_only();
    c.set(o.accel_axes[0]);
    c.set(o.accel_axes[1]);
    expect_covariance_equals_schuler(o, 1e-9);
  }
}

TEST(NavAccelCovariance, GyrosAndAccelerometersAddInVariance) {
  NavOptions o = accel_only(1.0);
  o.models = {Model::covariance};
  o.earth_rate = false;
  o.axes[1].coefficients.random_walk = present(1e-5);
  const double gyro = navigation_error(o).models[0].north_m.back();
  NavOptions a = accel_only(1.0);
  a.models = {Model::covariance};
  a.earth_rate = false;
  a.accel_axes[0].bias_m_s2 = 0.5 * kMg;
  const double accel = navigation_error(a).models[0].north_m.back();
  o.accel_axes[0] = a.accel_axes[0];
  const double both = navigation_error(o).models[0].north_m.back();
  EXPECT_NEAR(both * both / (gyro * gyro + accel * accel), 1.0, 1e-9);
}

TEST(NavAccelMonteCarlo, AgreesWithCovarianceWithinSamplingError) {
  NavOptions o = accel_only(1.0);
  o.runs = 300;
  o.seed = 5;
  o.models = {Model::covariance, Model::montecarlo};
  for (auto& a : o.accel_axes) {
    a.coefficients.random_walk = present(5e-4);
    a.coefficients.bias_instability = present(0.05 * kMg);
    a.coefficients.rate_random_walk = present(3e-6);
    a.bias_m_s2 = 0.2 * kMg;
  }
  o.axes[1].coefficients.random_walk = present(2e-7);  // ~0.1 km: the accelerometers dominate
  const NavResult r = navigation_error(o);
  const ModelSeries& cov = r.models[0];
  const MonteCarloStats& st = *r.models[1].montecarlo;
  double worst = 0.0;
  for (std::size_t i = 1; i < cov.t_s.size(); ++i) {
    const double zn = (st.ms_north_m2[i] - cov.north_m[i] * cov.north_m[i]) / st.se_ms_north_m2[i];
    const double ze = (st.ms_east_m2[i] - cov.east_m[i] * cov.east_m[i]) / st.se_ms_east_m2[i];
    worst = std::max({worst, std::abs(zn), std::abs(ze)});
    EXPECT_LT(std::abs(zn), 4.0) << "north at t = " << cov.t_s[i];
    EXPECT_LT(std::abs(ze), 4.0) << "east at t = " << cov.t_s[i];
  }
  std::printf("accelerometer montecarlo vs covariance, 300 runs: worst |z| = %.2f\n", worst);
  // The same runs without the accelerometers in the Monte Carlo would miss them: it can fail.
  NavOptions gyro_only = o;
  for (auto& a : gyro_only.accel_axes) a = AccelAxisNoise{};
  gyro_only.models = {Model::montecarlo};
  const double without = navigation_error(gyro_only).models[0].north_m.back();
  EXPECT_LT(without, 0.2 * cov.north_m.back());
}

TEST(NavAccelRequest, UnitsAndNamesAsTheEdgeSpellsThem) {
  NavRequest r;
  r.coefficients = {0, 1e-4, 0, 0, 0, 0, 0};
  r.coefficients_given = true;
  r.accel_coefficients = {0, 0, 50, 0, 0, 0, 0};
  r.accel_units = "ug";
  const NavOptions o = plan_navigation(r);
  EXPECT_DOUBLE_EQ(o.accel_axes[1].coefficients.bias_instability.value, 50e-6 * units::g_to_m_per_s2);
  EXPECT_EQ(o.accel_axes[1].coefficients.quantity, Quantity::acceleration);
  r.accel_units = "deg/s";
  try {
    plan_navigation(r);
    ADD_FAILURE() << "an angular rate was taken as the accelerometer unit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--accel-units deg/s is not an acceleration"), std::string::npos) << e.what();
  }
  r.accel_units = "mg";
  r.accel_coefficients.n = -1.0;
  r.names = {"", '_'};
  try {
    plan_navigation(r);
    ADD_FAILURE() << "a negative VRW was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("accel_N must be >= 0"), std::string::npos) << e.what();
  }
}

// A study document (analyze's report.json) gives the whole IMU: gyros and accelerometers by the
// units of their fits, on their axes by name; a single fit document, the gyros only.
nlohmann::json fit_doc(const std::string& unit, double n) {
  nlohmann::json terms;
  for (const char* t : {"Q", "N", "B", "K", "R"}) terms[t] = {{"value", nullptr}, {"identified", false}};
  terms["N"] = {{"value", n}, {"identified", true}};
  return {{"unit", unit}, {"terms", terms}};
}

TEST(NavAccelFrom, AStudyDocumentGivesEveryChannelItsAxis) {
  const nlohmann::json study{{"channels",
                              {{{"name", "acc_y"}, {"fit", fit_doc("m/s^2", 2e-3)}},
                               {{"name", "gyr_x"}, {"fit", fit_doc("deg/s", 1e-3)}},
                               {{"name", "acc_x"}, {"fit", fit_doc("mg", 3.0)}},
                               {{"name", "temp"}, {"fit", fit_doc("input unit", 1.0)}}}}};
  const ImuFits imu = imu_from_document(study, "report.json");
  EXPECT_EQ(imu.gyro_channels, (std::array<std::string, 3>{"gyr_x", "", ""}));
  EXPECT_EQ(imu.accel_channels, (std::array<std::string, 3>{"acc_x", "acc_y", ""}));
  EXPECT_NEAR(imu.accel[0]->coefficients.random_walk.value, 3e-3 * units::g_to_m_per_s2, 1e-15);
  EXPECT_DOUBLE_EQ(imu.accel[1]->coefficients.random_walk.value, 2e-3);
  EXPECT_FALSE(imu.accel[2].has_value());
  EXPECT_NEAR(imu.gyro[0]->coefficients.random_walk.value, 1e-3 * std::numbers::pi / 180.0, 1e-18);
  EXPECT_EQ(imu.gyro[1]->coefficients.random_walk.value, 0.0);
  NavRequest r;
  r.fitted_axes = imu.gyro;
  r.fitted_accel_axes = imu.accel;
  EXPECT_EQ(plan_navigation(r).accel_axes[1].coefficients.random_walk.value, 2e-3);
  r.accel_coefficients.n = 1.0;
  EXPECT_THROW(plan_navigation(r), InputError);
  // One fit document: that gyro on every axis, no accelerometers.
  const ImuFits one = imu_from_document(fit_doc("deg/s", 1e-3), "fit.json");
  EXPECT_TRUE(one.gyro[2].has_value());
  EXPECT_FALSE(one.accel[0].has_value());
  const nlohmann::json no_gyro{{"channels", {{{"name", "acc_x"}, {"fit", fit_doc("m/s^2", 1e-3)}}}}};
  EXPECT_THROW(imu_from_document(no_gyro, "report.json"), InputError);
}

TEST(NavAccelCli, AccelerometerFlagsReachTheModelsAndTheDocument) {
  const auto run = test::run_cli({"nav", "--accel-N", "0.03", "--accel-bias", "1", "--accel-units", "mg", "--model",
                                  "schuler,covariance", "--no-earth-rate", "--format", "json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  ASSERT_TRUE(doc.contains("accel_axes"));
  EXPECT_NEAR(doc["accel_axes"][0]["bias_m_s2"].get<double>(), 1e-3 * units::g_to_m_per_s2, 1e-15);
  EXPECT_NEAR(doc["accel_axes"][0]["N_m_s_sqrt_s"].get<double>(), 0.03e-3 * units::g_to_m_per_s2, 1e-15);
  const double schuler = doc["models"][0]["path_m"].back().get<double>();
  const double covariance = doc["models"][1]["path_m"].back().get<double>();
  EXPECT_GT(schuler, 100.0);
  EXPECT_NEAR(covariance / schuler, 1.0, 1e-9);
  EXPECT_NE(run.err.find("down (z) accelerometer"), std::string::npos) << run.err;
  const auto bad = test::run_cli({"nav", "--accel-N", "1", "--accel-units", "deg/s"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--accel-units deg/s is not an acceleration"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace imunoise::nav
