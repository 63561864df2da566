// Fleet statistics against hand-computed values: type-7 quantiles (NumPy's default) and the
// Iglewicz-Hoaglin robust z-score; and the fleet document's flags, reasons and pass rate on
// fit documents built by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/fleet/fleet.hpp"
#include "imunoise/fleet/statistics.hpp"

namespace imunoise::fleet {
namespace {

TEST(FleetStatistics, QuantilesInterpolateBetweenOrderStatistics) {
  // 1..11: h = 10 p, so p05 = 1.5, q25 = 3.5, median 6, q75 = 8.5, p95 = 10.5.
  std::vector<double> v{11, 3, 5, 1, 9, 2, 10, 4, 8, 6, 7};
  const auto q = quantiles(v);
  EXPECT_EQ(q.n, 11u);
  EXPECT_DOUBLE_EQ(q.p05, 1.5);
  EXPECT_DOUBLE_EQ(q.q25, 3.5);
  EXPECT_DOUBLE_EQ(q.median, 6.0);
  EXPECT_DOUBLE_EQ(q.q75, 8.5);
  EXPECT_DOUBLE_EQ(q.p95, 10.5);
  // Even count: numpy.percentile([1, 2, 3, 4], 50) = 2.5, 25 -> 1.75.
  const std::vector<double> even{4, 1, 3, 2};
  EXPECT_DOUBLE_EQ(quantiles(even).median, 2.5);
  EXPECT_DOUBLE_EQ(quantiles(even).q25, 1.75);
  EXPECT_DOUBLE_EQ(quantiles(std::vector<double>{7.0}).p95, 7.0);
  EXPECT_THROW(quantiles(std::vector<double>{}), InputError);
  EXPECT_THROW(quantiles(std::vector<double>{1.0, NAN}), InputError);
}

TEST(FleetStatistics, RobustZIsMadScaled) {
  // median 3, |x - 3| = 2 1 0 1 97: MAD = 1, z = 0.6745 (x - 3).
  const auto z = robust_z(std::vector<double>{1, 2, 3, 4, 100});
  EXPECT_NEAR(z[0], -2 * 0.6745, 1e-12);
  EXPECT_NEAR(z[4], 97 * 0.6745, 1e-12);
  EXPECT_DOUBLE_EQ(z[2], 0.0);
  // More than half equal: MAD = 0, mean absolute deviation (8/5) x sqrt(pi/2) is the scale.
  const auto z0 = robust_z(std::vector<double>{5, 5, 5, 5, 13});
  EXPECT_NEAR(z0[4], 8.0 / (1.6 * std::sqrt(M_PI / 2.0)), 1e-12);
  for (const double v : robust_z(std::vector<double>{2, 2, 2})) EXPECT_EQ(v, 0.0);
}

nlohmann::json fit_doc(double n_value, double half_width, const char* verdict = "pass") {
  nlohmann::json term{{"value", n_value}, {"ci_low", n_value - half_width},
                      {"ci_high", n_value + half_width}, {"identified", true}, {"fitted", true},
                      {"unit", "deg/sqrt(s)"}};
  nlohmann::json spec_term{{"symbol", "N"}, {"verdict", verdict}, {"deviation_percent", 12.5},
                           {"conclusive", true},
                           {"measured_in_spec_unit", {{"value", 0.05625}, {"unit", "deg/sqrt(h)"}}},
                           {"spec", {{"value", 0.05}, {"unit", "deg/sqrt(h)"}}}};
  return {{"rate_hz", 100.0}, {"n_samples", 1000}, {"unit", "deg/s"},
          {"terms", {{"N", term}}},
          {"spec_comparison", {{"spec", "tg100"}, {"all_pass", std::string(verdict) == "pass"},
                               {"terms", {spec_term}}}}};
}

TEST(FleetDocument, FlagsOutliersFailuresAndErrorsWithReasons) {
  std::vector<SensorOutcome> sensors;
  for (const double n : {1.00, 1.02, 0.98, 1.01, 0.99}) sensors.push_back({"ok" + std::to_string(n), fit_doc(n * 1e-3, 1e-5), ""});
  sensors.push_back({"far.txt", fit_doc(3e-3, 1e-5, "fail"), ""});
  sensors.push_back({"wide.txt", fit_doc(2e-3, 1.5e-3), ""});  // far, but its interval holds the median
  sensors.push_back({"bad.txt", nullptr, "bad.txt:3: not a number"});
  const auto doc = fleet_document(sensors);
  const auto& far = doc["sensors"][5];
  EXPECT_EQ(far["flags"], nlohmann::json({"outlier", "datasheet_fail"}));
  EXPECT_NE(far["reasons"][0].get<std::string>().find("N = 0.003 deg/sqrt(s) is an outlier"), std::string::npos)
      << far["reasons"][0];
  EXPECT_NE(far["reasons"][1].get<std::string>().find("+12.5 %"), std::string::npos);
  EXPECT_TRUE(doc["sensors"][6]["flags"].empty()) << doc["sensors"][6]["flags"];
  EXPECT_EQ(doc["sensors"][7]["flags"], nlohmann::json({"error"}));
  EXPECT_TRUE(doc["sensors"][7]["fit"].is_null());
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(doc["sensors"][i]["flags"].empty());
  const auto& summary = doc["summary"];
  EXPECT_EQ(summary["n_files"], 8);
  EXPECT_EQ(summary["n_analysed"], 7);
  EXPECT_EQ(summary["n_failed"], 1);
  EXPECT_EQ(summary["outliers"], nlohmann::json({"far.txt"}));
  EXPECT_EQ(summary["datasheet"]["n_pass"], 6);
  EXPECT_EQ(summary["datasheet"]["n_judged"], 7);
  EXPECT_DOUBLE_EQ(summary["datasheet"]["pass_rate"].get<double>(), 6.0 / 7.0);
  // 7 identified N values: 0.98 0.99 1.00 1.01 1.02 2 3 (x1e-3): median 1.01e-3.
  EXPECT_NEAR(summary["coefficients"]["N"]["distribution"]["median"].get<double>(), 1.01e-3, 1e-15);
  const std::string csv = fleet_csv(doc);
  EXPECT_NE(csv.find("N [deg/sqrt(s)]"), std::string::npos);
  EXPECT_NE(csv.find("bad.txt,error,"), std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
}

TEST(FleetDocument, NoOutlierTestBelowFiveSensors) {
  std::vector<SensorOutcome> sensors{{"a", fit_doc(1e-3, 1e-6), ""}, {"b", fit_doc(1.01e-3, 1e-6), ""},
                                     {"c", fit_doc(9e-3, 1e-6), ""}};
  const auto doc = fleet_document(sensors);
  EXPECT_TRUE(doc["summary"]["outliers"].empty());
}

}  // namespace
}  // namespace imunoise::fleet
