// Fused-axis noise and the detection design against closed forms.
#include <algorithm>
#include <cmath>
#include <utility>
#include <numbers>

#include <gtest/gtest.h>

#include "imunoise/error.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/detection.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/redundant/report.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;

SensorModel model(double n, double b, double k, double q = 0.0) {
  SensorModel m;
  m.source = "model";
  auto set = [](Coefficient& c, double v) {
    c.value = v;
    c.ci_low = 0.9 * v;
    c.ci_high = 1.1 * v;
    c.identified = v > 0;
  };
  set(m.coefficients.quantization, q);
  set(m.coefficients.random_walk, n);
  set(m.coefficients.bias_instability, b);
  set(m.coefficients.rate_random_walk, k);
  return m;
}

TEST(RedundantAnalysis, IdenticalSensorsOnTetraScaleEveryTermByTheGain) {
  const std::vector<SensorModel> s(4, model(1.5e-5, 1.0e-5, 2.6e-7, 1e-6));
  const Analysis a = analyze_unit(make_geometry("tetra"), s);
  ASSERT_TRUE(a.axes.has_value());
  const double g = std::sqrt(3.0) / 2.0;
  for (const auto& axis : *a.axes) {
    EXPECT_NEAR(axis.random_walk.value, g * 1.5e-5, 1e-18);
    EXPECT_NEAR(axis.bias_instability.value, g * 1.0e-5, 1e-18);
    EXPECT_NEAR(axis.rate_random_walk.value, g * 2.6e-7, 1e-20);
    EXPECT_NEAR(axis.quantization.value, g * 1e-6, 1e-19);
    EXPECT_NEAR(axis.random_walk.ci_low, g * 0.9 * 1.5e-5, 1e-18);
    EXPECT_NEAR(axis.random_walk.ci_high, g * 1.1 * 1.5e-5, 1e-18);
    EXPECT_TRUE(axis.random_walk.identified);
    EXPECT_FALSE(axis.rate_ramp.identified);
  }
}

TEST(RedundantAnalysis, WeightedFusionIsTheBestLinearUnbiasedEstimate) {
  // With W = diag(1/N_i^2), sum_i G_ji^2 N_i^2 = [(H^T W H)^-1]_jj (Gauss-Markov theorem),
  // and it is below the equal-weight value.
  const Geometry g = make_geometry("cone:5:60");
  std::vector<SensorModel> s;
  const double n[5] = {1e-5, 2e-5, 1.5e-5, 4e-5, 1e-5};
  for (double v : n) s.push_back(model(v, 0, 0));
  const Analysis a = analyze_unit(g, s);
  ASSERT_TRUE(a.weighted);
  double m[3][3] = {};
  for (std::size_t i = 0; i < 5; ++i) {
    for (int r = 0; r < 3; ++r) for (int c = 0; c < 3; ++c) m[r][c] += g.axes[i][r] * g.axes[i][c] / (n[i] * n[i]);
  }
  // Diagonal of the inverse by cofactors.
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  const double inv_diag[3] = {(m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det,
                              (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det};
  AnalysisOptions equal;
  equal.weight_by_noise = false;
  const Analysis e = analyze_unit(g, s, equal);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_NEAR((*a.axes)[j].random_walk.value, std::sqrt(inv_diag[j]), 1e-12 * std::sqrt(inv_diag[j]));
    EXPECT_LT((*a.axes)[j].random_walk.value, (*e.axes)[j].random_walk.value);
  }
}

// The frequency-domain definition, integrated numerically (independent of the closed form):
// (1/pi) int_0^inf |H(f)|^2 df / f, Simpson steps of at most 1% in f and 1/(40 (a+b)) (the
// cross term's oscillation), the tail beyond 400/min(a,b) by its average.
double flicker_integral(double a, double b) {
  auto sinc = [](double x) { return std::abs(x) < 1e-8 ? 1.0 : std::sin(x) / x; };
  const double pi = std::numbers::pi, span = a + b;
  auto g = [&](double f) {
    const double sa = sinc(pi * f * a), sb = sinc(pi * f * b);
    return (sa * sa + sb * sb - 2 * sa * sb * std::cos(pi * f * span)) / f;
  };
  const double f_lo = 1e-4 / span, f_hi = 400 / std::min(a, b);
  double sum = 0.5 * std::pow(pi * f_lo * span, 2), f = f_lo, gf = g(f);
  while (f < f_hi) {
    const double h = std::min({0.01 * f, 1 / (40 * span), f_hi - f});
    const double g1 = g(f + h);
    sum += h / 6 * (gf + 4 * g(f + h / 2) + g1);
    f += h;
    gf = g1;
  }
  sum += (1 / (a * a) + 1 / (b * b)) / (2 * pi * pi) / (2 * f_hi * f_hi);
  return sum / pi;
}

TEST(RedundantAnalysis, FlickerDifferenceVarianceClosedForm) {
  // a = b = tau: twice the Allan variance of flicker, 2 (2 ln 2 / pi), for any tau.
  for (double tau : {0.01, 1.0, 300.0}) {
    EXPECT_NEAR(flicker_difference_variance(tau, tau), 4.0 * std::numbers::ln2 / std::numbers::pi, 1e-14);
  }
  // Scale invariance of 1/f noise: F(c a, c b) = F(a, b).
  EXPECT_NEAR(flicker_difference_variance(1.0, 60.0), flicker_difference_variance(10.0, 600.0), 1e-12);
  // Against the frequency-domain integral, unequal windows.
  for (const auto& [a, b] : {std::pair{1.0, 1.0}, std::pair{1.0, 5.0}, std::pair{0.3, 2.0}}) {
    EXPECT_NEAR(flicker_difference_variance(a, b), flicker_integral(a, b), 2e-6) << a << " " << b;
  }
  EXPECT_GT(flicker_difference_variance(1.0, 60.0), flicker_difference_variance(1.0, 1.0));
}

TEST(RedundantAnalysis, DetectionDesignFollowsTheFalseAlarmRate) {
  DetectionOptions o;  // 1 s window, 0.01 false alarms per hour
  const std::vector<SensorModel> s(6, model(1.5e-5, 0, 0));
  AnalysisOptions ao;
  ao.detection = o;
  const Analysis a = analyze_unit(make_geometry("cone:6:54.7356"), s, ao);
  EXPECT_NEAR(a.detection.per_test_probability, 0.01 / 3600.0, 1e-18);
  EXPECT_EQ(a.detection.dof, 3u);
  // chi2_3 upper quantile at 2.7778e-6 (independent: Wilson-Hilferty is too coarse here; the
  // survival function at the threshold must equal the probability): chi2_3 sf(x) =
  // erfc(sqrt(x/2)) + sqrt(2x/pi) exp(-x/2).
  const double x = a.detection.threshold;
  const double sf = std::erfc(std::sqrt(x / 2)) + std::sqrt(2 * x / std::numbers::pi) * std::exp(-x / 2);
  EXPECT_NEAR(sf / a.detection.per_test_probability, 1.0, 1e-9);
  // White noise only: sigma of (window - reference) = N sqrt(1/a + 1/b); MDF from lambda.
  const double sd = 1.5e-5 * std::sqrt(1.0 + 1.0 / 60.0);
  for (double v : a.detection.sigma_difference_rad_s) EXPECT_NEAR(v, sd, 1e-15);
  // Isotropic cone of 6: every parity column has |v_i|^2 = 1 - 3/6.
  for (double mdf : a.min_detectable_fault_rad_s) EXPECT_NEAR(mdf, std::sqrt(a.detection.noncentrality / 0.5) * sd, 1e-12);
  for (double w : a.min_detectable_fault_window_sigma) {
    EXPECT_NEAR(w, std::sqrt(a.detection.noncentrality * (1 + 1.0 / 60.0) / 0.5), 1e-9);
  }
  // 3+1 has no isolation and the triad's sensors are all in the parity space.
  const Analysis t = analyze_unit(make_geometry("3+1"), std::vector<SensorModel>(4, model(1.5e-5, 0, 0)), ao);
  EXPECT_FALSE(t.isolable);
  for (double mdf : t.min_detectable_fault_rad_s) EXPECT_TRUE(std::isfinite(mdf));
}

TEST(RedundantAnalysis, ReportJsonCarriesTheContractFields) {
  const std::vector<SensorModel> s(4, model(1.5e-5, 1e-5, 2e-7));
  const Analysis a = analyze_unit(make_geometry("tetra"), s);
  const auto j = report_json(a, parse_unit("deg/s"));
  for (const char* key : {"geometry", "H", "axis_gain", "gdop", "parity", "axes", "gdop_without",
                          "min_detectable_fault", "false_alarm_per_hour"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["geometry"], "tetra");
  EXPECT_NEAR(j["gdop"].get<double>(), 1.5, 1e-12);
  EXPECT_EQ(j["axes"].size(), 3u);
  const double deg = std::numbers::pi / 180;
  EXPECT_NEAR(j["axes"][0]["N"]["value"].get<double>(), std::sqrt(0.75) * 1.5e-5 / deg, 1e-12);
  EXPECT_EQ(j["axes"][0]["N"]["unit"], "deg/sqrt(s)");
  EXPECT_EQ(j["axes"][0]["N"]["customary"]["unit"], "deg/sqrt(h)");
  EXPECT_FALSE(j.dump().find("NaN") != std::string::npos);
}

TEST(RedundantAnalysis, ReportSaysWhenTheRecordIsTooShortToTest) {
  const std::vector<SensorModel> s(4, model(1.5e-5, 0, 0));
  const Geometry g = make_geometry("tetra");
  const Analysis a = analyze_unit(g, s);
  FaultDetector d(g, s, 100.0, DetectionOptions{});
  std::vector<std::vector<double>> rec(4, std::vector<double>(3000, 0.0));  // 30 s < 61 s
  std::vector<std::span<const double>> spans(rec.begin(), rec.end());
  d.push(spans);
  EXPECT_EQ(d.result().tests, 0u);
  const auto j = report_json(a, parse_unit("deg/s"), &d.result());
  EXPECT_NE(j["notes"].dump().find("no detection test was made"), std::string::npos) << j["notes"].dump();
}

TEST(RedundantAnalysis, FitDocumentsAreRead) {
  nlohmann::json doc = {{"unit", "deg/s"},
                        {"level", 0.95},
                        {"terms", {{"N", {{"value", 8.9e-4}, {"ci_low", 8.8e-4}, {"ci_high", 9.0e-4}, {"identified", true}}},
                                   {"B", {{"value", 5.9e-4}, {"ci_low", nullptr}, {"ci_high", 7e-4}, {"identified", true}}},
                                   {"K", {{"value", 0}, {"identified", false}}}}}};
  Unit u;
  const SensorModel m = sensor_model_from_fit_json(doc, "g1.json", u);
  EXPECT_EQ(u.name, "deg/s");
  EXPECT_NEAR(m.coefficients.random_walk.value, 8.9e-4 * std::numbers::pi / 180, 1e-18);
  EXPECT_FALSE(m.coefficients.rate_random_walk.identified);
  EXPECT_THROW(sensor_model_from_fit_json(nlohmann::json{{"x", 1}}, "bad.json", u), InputError);
  nlohmann::json accel = doc;
  accel["unit"] = "m/s^2";
  EXPECT_THROW(sensor_model_from_fit_json(accel, "acc.json", u), InputError);
}

}  // namespace

