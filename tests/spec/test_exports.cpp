// Kalibr imu.yaml and Kalman-filter JSON exports: units, round trips through the written text,
// and the numbers of references.md.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "imunoise/error.hpp"
#include "imunoise/spec/exports.hpp"
#include "imunoise/spec/spec.hpp"

namespace imunoise {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

void expect_rel(double actual, double expected, double rel = 1e-12) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << "expected " << expected;
}

Coefficient coefficient(double value_si) {
  Coefficient c;
  c.value = value_si;
  c.identified = true;
  c.ci_low = 0.98 * value_si;
  c.ci_high = 1.02 * value_si;
  return c;
}

// Gyro 1 of the paper's Table 2: N = 8.9e-4 deg/sqrt(s), B = 5.9e-4 deg/s, K = 1.5e-5
// deg/s/sqrt(s).
NoiseCoefficients gyro1() {
  NoiseCoefficients c;
  c.random_walk = coefficient(8.9e-4 * deg);
  c.bias_instability = coefficient(5.9e-4 * deg);
  c.rate_random_walk = coefficient(0.15e-4 * deg);
  return c;
}

TEST(Units, ReferencesMdArwNumbers) {
  const double n_si = 8.9e-4 * deg;  // deg/sqrt(s) -> rad/sqrt(s)
  EXPECT_NEAR(n_si, 1.553e-5, 0.0005e-5);
  EXPECT_NEAR(n_si / customary_gyro_N.to_si, 0.0534, 1e-12);  // deg/sqrt(h)
  // Discrete white-noise sigma at 200 Hz: 8.9e-4 / sqrt(0.005) = 0.0126 deg/s.
  const auto kf = kalman_parameters(gyro1(), 200.0);
  EXPECT_NEAR(kf["white_noise"]["discrete_sigma"]["value"].get<double>() / deg, 0.012586, 1e-6);
  EXPECT_EQ(kf["white_noise"]["discrete_sigma"]["unit"], "rad/s");
}

TEST(Units, DensityRoundTripsThroughSpecUnits) {
  // deg/sqrt(h) <-> rad/s/sqrt(Hz) <-> deg/s/sqrt(Hz) (two- and one-sided) <-> ug/sqrt(Hz).
  std::mt19937_64 rng(20260522);
  std::uniform_real_distribution<double> exponent(-8.0, 2.0);
  const auto f = [](char symbol, SensorKind s, const char* unit, PsdConvention p) {
    return spec_term_to_si(symbol, s, unit, p);
  };
  for (int i = 0; i < 200; ++i) {
    const double x = std::pow(10.0, exponent(rng));
    const double via_h =
        x * f('N', SensorKind::gyroscope, "deg/sqrt(h)", PsdConvention::not_applicable);
    const double in_kalibr =
        via_h / f('N', SensorKind::gyroscope, "rad/s/sqrt(Hz)", PsdConvention::two_sided);
    const double back = in_kalibr *
                        f('N', SensorKind::gyroscope, "rad/s/sqrt(Hz)", PsdConvention::two_sided) /
                        f('N', SensorKind::gyroscope, "deg/sqrt(h)", PsdConvention::not_applicable);
    expect_rel(back, x);
    const double one_sided =
        via_h / f('N', SensorKind::gyroscope, "deg/s/sqrt(Hz)", PsdConvention::one_sided);
    expect_rel(one_sided, x / 60.0 * std::numbers::sqrt2);  // x deg/sqrt(h) = x/60 deg/sqrt(s)
    const double ug =
        x * f('N', SensorKind::accelerometer, "ug/sqrt(Hz)", PsdConvention::two_sided);
    expect_rel(ug / f('N', SensorKind::accelerometer, "m/s^2/sqrt(Hz)", PsdConvention::two_sided),
               x * 9.80665e-6);
    const double k =
        x * f('K', SensorKind::gyroscope, "deg/h/sqrt(h)", PsdConvention::not_applicable);
    expect_rel(k / f('K', SensorKind::gyroscope, "deg/s/sqrt(s)", PsdConvention::not_applicable),
               x / 216000.0);  // references.md: deg/s/sqrt(s) x 216000 = deg/h/sqrt(h)
  }
}

TEST(RoundTripNumber, ShortestExactAndYaml11Float) {
  EXPECT_EQ(round_trip_number(200.0), "200.0");
  EXPECT_EQ(round_trip_number(3e-05), "3.0e-05");
  EXPECT_EQ(round_trip_number(1.5), "1.5");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-12.0, 6.0);
  for (int i = 0; i < 1000; ++i) {
    const double x = std::pow(10.0, exponent(rng));
    EXPECT_EQ(std::stod(round_trip_number(x)), x);
  }
}

TEST(Kalibr, WritesKeysInKalibrUnitsAndParsesBackExactly) {
  const auto g = gyro1();
  NoiseCoefficients a;
  a.quantity = Quantity::acceleration;
  a.random_walk = coefficient(60e-6 * 9.80665);  // 60 ug/sqrt(Hz)
  a.rate_random_walk = coefficient(4e-5);        // m/s^3/sqrt(Hz)
  for (const double inflation : {1.0, 2.0, 10.0 / 3.0}) {
    const std::string text = kalibr_imu_yaml(g, &a, 200.0, inflation, "/imu0");
    const YAML::Node y = YAML::Load(text);
    expect_rel(y["gyroscope_noise_density"].as<double>(), g.random_walk.value * inflation);
    expect_rel(y["gyroscope_random_walk"].as<double>(), g.rate_random_walk.value * inflation);
    expect_rel(y["accelerometer_noise_density"].as<double>(), a.random_walk.value * inflation);
    expect_rel(y["accelerometer_random_walk"].as<double>(), a.rate_random_walk.value * inflation);
    EXPECT_EQ(y["update_rate"].as<double>(), 200.0);
    EXPECT_EQ(y["rostopic"].as<std::string>(), "/imu0");
    EXPECT_NE(text.find("# imunoise inflation factor: " + round_trip_number(inflation)),
              std::string::npos);
    // The raw values are recorded in comments, exactly.
    EXPECT_NE(text.find("raw N = " + round_trip_number(g.random_walk.value) + " rad/s/sqrt(Hz)"),
              std::string::npos)
        << text;
    // Back to customary units: N x inflation in deg/sqrt(h).
    expect_rel(y["gyroscope_noise_density"].as<double>() / inflation / customary_gyro_N.to_si,
               0.0534);
  }
  // references.md: gyroscope_noise_density of 8.9e-4 deg/sqrt(s) = 1.553e-5.
  const YAML::Node y = YAML::Load(kalibr_imu_yaml(g, &a, 200.0, 1.0, "/imu0"));
  EXPECT_NEAR(y["gyroscope_noise_density"].as<double>(), 1.553e-5, 0.0005e-5);
}

TEST(Kalibr, MissingAccelerometerAndUnidentifiedTermsAreNotInvented) {
  NoiseCoefficients g = gyro1();
  g.rate_random_walk = Coefficient{};
  g.rate_random_walk.note = "record too short";
  const std::string text = kalibr_imu_yaml(g, nullptr, 100.0, 1.5, "");
  const YAML::Node y = YAML::Load(text);
  EXPECT_TRUE(y["gyroscope_noise_density"]);
  EXPECT_FALSE(y["gyroscope_random_walk"]);
  EXPECT_FALSE(y["accelerometer_noise_density"]);
  EXPECT_FALSE(y["accelerometer_random_walk"]);
  EXPECT_NE(text.find("# accelerometer_noise_density: <FILL IN>"), std::string::npos) << text;
  EXPECT_NE(text.find("# gyroscope_random_walk: <FILL IN>"), std::string::npos) << text;
  EXPECT_NE(text.find("NOT MEASURED"), std::string::npos);
  EXPECT_NE(text.find("record too short"), std::string::npos);
  EXPECT_EQ(y["rostopic"].as<std::string>(), "/imu0");
  EXPECT_EQ(y["update_rate"].as<double>(), 100.0);
}

TEST(Kalibr, RejectsBadArguments) {
  const auto g = gyro1();
  EXPECT_THROW((void)kalibr_imu_yaml(g, nullptr, 0.0, 1.0, "/imu0"), InputError);
  EXPECT_THROW((void)kalibr_imu_yaml(g, nullptr, 200.0, 0.0, "/imu0"), InputError);
  EXPECT_THROW((void)kalibr_imu_yaml(g, nullptr, 200.0, std::nan(""), "/imu0"), InputError);
  EXPECT_THROW((void)kalibr_imu_yaml(g, &g, 200.0, 1.0, "/imu0"), InputError);  // gyro as accel
  NoiseCoefficients a;
  a.quantity = Quantity::acceleration;
  EXPECT_THROW((void)kalibr_imu_yaml(a, nullptr, 200.0, 1.0, "/imu0"), InputError);
}

TEST(GaussMarkov, AllanPeakConstants) {
  // Scan the Allan deviation of a unit GM (sigma = 1, T_c = 1) for its maximum.
  double best = 0.0;
  double best_tau = 0.0;
  for (double tau = 1.0; tau < 4.0; tau += 1e-4) {
    const double a = gauss_markov_adev(1.0, 1.0, tau);
    if (a > best) {
      best = a;
      best_tau = tau;
    }
  }
  EXPECT_NEAR(best, kGaussMarkovPeakRatio, 1e-4);
  EXPECT_NEAR(best_tau, kGaussMarkovPeakTau, 1e-3);
  // Asymptotes: white-noise-like sigma^2 T_c ... for tau >> T_c the variance -> 2 sigma^2 T_c /
  // tau.
  expect_rel(gauss_markov_adev(2.0, 3.0, 3e6), std::sqrt(2.0 * 4.0 * 3.0 / 3e6), 1e-5);
}

TEST(Kalman, ParametersOfPaperGyro1) {
  const auto c = gyro1();
  const auto j = kalman_parameters(c, 200.0);
  EXPECT_EQ(j["sensor"], "gyroscope");
  EXPECT_EQ(j["dt_s"].get<double>(), 0.005);
  const double n = c.random_walk.value;
  const double k = c.rate_random_walk.value;
  const double b = c.bias_instability.value;
  expect_rel(j["white_noise"]["psd"]["value"].get<double>(), n * n);
  EXPECT_EQ(j["white_noise"]["psd"]["unit"], "rad^2/s");
  expect_rel(j["white_noise"]["discrete_sigma"]["value"].get<double>(), n / std::sqrt(0.005));
  expect_rel(j["rate_random_walk"]["psd"]["value"].get<double>(), k * k);
  EXPECT_EQ(j["rate_random_walk"]["psd"]["unit"], "rad^2/s^3");
  expect_rel(j["rate_random_walk"]["discrete_sigma"]["value"].get<double>(), k * std::sqrt(0.005));
  // Gauss-Markov matched to the floor at tau_opt = sqrt(3) N / K = 102.8 s (references.md).
  const auto& gm = j["bias_instability"];
  EXPECT_EQ(gm["model"], "first_order_gauss_markov");
  const double sigma = gm["sigma"]["value"].get<double>();
  const double tc = gm["correlation_time"]["value"].get<double>();
  EXPECT_NEAR(sigma / b, 1.0760, 1e-4);
  EXPECT_NEAR(tc * kGaussMarkovPeakTau, 102.8, 0.05);
  EXPECT_EQ(gm["correlation_time"]["unit"], "s");
  // The matched GM's Allan peak is the bias-instability floor sqrt(2 ln2/pi) B at tau_opt.
  expect_rel(gauss_markov_adev(sigma, tc, kGaussMarkovPeakTau * tc),
             std::sqrt(2.0 * std::numbers::ln2 / std::numbers::pi) * b, 2e-4);
  const double phi = std::exp(-0.005 / tc);
  expect_rel(gm["discrete_phi"]["value"].get<double>(), phi);
  expect_rel(gm["discrete_sigma"]["value"].get<double>(), sigma * std::sqrt(1.0 - phi * phi));
  expect_rel(gm["driving_psd"]["value"].get<double>(), 2.0 * sigma * sigma / tc);
  // Every number carries a unit.
  for (const char* block : {"white_noise", "bias_instability", "rate_random_walk"}) {
    for (const auto& [key, value] : j[block].items()) {
      if (value.is_object() && value.contains("value")) {
        EXPECT_TRUE(value.contains("unit")) << block << "." << key;
      }
    }
  }
  // JSON text round trip is exact.
  const auto reparsed = nlohmann::json::parse(j.dump());
  EXPECT_EQ(reparsed["white_noise"]["psd"]["value"].get<double>(),
            j["white_noise"]["psd"]["value"].get<double>());
}

TEST(Kalman, FloorTauFittedGaussMarkovAndMissingTerms) {
  auto c = gyro1();
  const auto given = kalman_parameters(c, 200.0, 50.0);
  expect_rel(given["bias_instability"]["correlation_time"]["value"].get<double>(),
             50.0 / kGaussMarkovPeakTau);

  c.gauss_markov = {GaussMarkovTerm{coefficient(1e-4), coefficient(30.0)}};
  const auto fitted = kalman_parameters(c, 200.0);
  EXPECT_EQ(fitted["bias_instability"]["sigma"]["value"].get<double>(), 1e-4);
  EXPECT_EQ(fitted["bias_instability"]["correlation_time"]["value"].get<double>(), 30.0);

  NoiseCoefficients none;
  none.random_walk = coefficient(1e-5);
  none.bias_instability = coefficient(1e-5);  // no K: T_c unknown
  const auto partial = kalman_parameters(none, 100.0);
  EXPECT_TRUE(partial["bias_instability"]["correlation_time"]["value"].is_null());
  EXPECT_TRUE(partial["bias_instability"]["sigma"]["value"].is_number());
  EXPECT_TRUE(partial["rate_random_walk"]["psd"]["value"].is_null());
  EXPECT_TRUE(partial["rate_random_walk"].contains("note"));

  NoiseCoefficients accel;
  accel.quantity = Quantity::acceleration;
  accel.random_walk = coefficient(1e-3);
  const auto a = kalman_parameters(accel, 100.0);
  EXPECT_EQ(a["white_noise"]["psd"]["unit"], "m^2/s^3");
  EXPECT_EQ(a["white_noise"]["discrete_sigma"]["unit"], "m/s^2");

  EXPECT_THROW((void)kalman_parameters(c, -1.0), InputError);
  EXPECT_THROW((void)kalman_parameters(c, 200.0, 0.0), InputError);
}

// Several Gauss-Markov terms (a gmwm fit): one Kalman-filter state each, in the fit's order (by
// T_c), bias_instability the first; a term not identified gives no state. Kalibr cannot carry
// them: its file says so, naming each term, and not_carried says the same for the warnings.
TEST(Kalman, OneStatePerGaussMarkovTermAndKalibrSaysWhatItDrops) {
  auto c = gyro1();
  Coefficient dropped;  // a term the fit reported but did not identify
  c.gauss_markov = {GaussMarkovTerm{coefficient(1e-4), coefficient(2.0)},
                    GaussMarkovTerm{dropped, dropped},
                    GaussMarkovTerm{coefficient(5e-5), coefficient(40.0)}};
  const auto j = kalman_parameters(c, 200.0);
  const auto& states = j["gauss_markov_states"];
  ASSERT_EQ(states.size(), 2u) << j.dump(1);
  EXPECT_EQ(states[0]["correlation_time"]["value"].get<double>(), 2.0);
  EXPECT_EQ(states[1]["sigma"]["value"].get<double>(), 5e-5);
  expect_rel(states[1]["discrete_phi"]["value"].get<double>(), std::exp(-0.005 / 40.0));
  expect_rel(states[1]["driving_psd"]["value"].get<double>(), 2.0 * 5e-5 * 5e-5 / 40.0);
  EXPECT_EQ(j["bias_instability"]["sigma"]["value"].get<double>(), 1e-4);
  // Without fitted terms: the one matched to B is the only state.
  const auto matched = kalman_parameters(gyro1(), 200.0);
  ASSERT_EQ(matched["gauss_markov_states"].size(), 1u);
  EXPECT_EQ(matched["gauss_markov_states"][0]["sigma"]["value"].get<double>(),
            matched["bias_instability"]["sigma"]["value"].get<double>());

  const auto lines = not_carried(c, "Kalibr");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("2 Gauss-Markov terms"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("T_c 40 s"), std::string::npos) << lines[0];
  const std::string yaml = kalibr_imu_yaml(c, nullptr, 200.0, 1.0, "/imu0");
  EXPECT_NE(yaml.find(lines[0]), std::string::npos) << yaml;
  EXPECT_TRUE(not_carried(gyro1(), "Kalibr").empty());
}

}  // namespace
}  // namespace imunoise
