// Fleet statistics against hand-computed values: type-7 quantiles (NumPy's default) and the
// Iglewicz-Hoaglin robust z-score; and the fleet document's flags, reasons and pass rate on
// sensor summaries built by hand; and the outcome's bytes between ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/fleet/fleet.hpp"
#include "imunoise/fleet/outcome_wire.hpp"
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

// A sensor whose fit identified N (and nothing else) and whose datasheet verdict on N is given.
SensorOutcome sensor(const std::string& file, double n_value, double half_width, const char* verdict = "pass") {
  SensorSummary summary;
  summary.rate_hz = 100.0;
  summary.n_samples = 1000;
  summary.unit = "deg/s";
  const char* names[] = {"Q", "N", "B", "K", "R"};
  for (std::size_t j = 0; j < 5; ++j) summary.terms[j] = {names[j], "unit", 0.0, NAN, NAN, false, false};
  summary.terms[1] = {"N", "deg/sqrt(s)", n_value, n_value - half_width, n_value + half_width, true, true};
  summary.datasheet = DatasheetSummary{
      "tg100", std::string(verdict) == "pass", {{"N", verdict, 0.05625, "deg/sqrt(h)", 12.5, 0.05, "deg/sqrt(h)", true}}};
  return {file, summary, nlohmann::json{{"file", file}}, ""};
}

SensorOutcome failure(const std::string& file, const std::string& error) { return {file, std::nullopt, nullptr, error}; }

TEST(FleetDocument, FlagsOutliersFailuresAndErrorsWithReasons) {
  std::vector<SensorOutcome> sensors;
  for (const double n : {1.00, 1.02, 0.98, 1.01, 0.99}) sensors.push_back(sensor("ok" + std::to_string(n), n * 1e-3, 1e-5));
  sensors.push_back(sensor("far.txt", 3e-3, 1e-5, "fail"));
  sensors.push_back(sensor("wide.txt", 2e-3, 1.5e-3));  // far, but its interval holds the median
  sensors.push_back(failure("bad.txt", "bad.txt:3: not a number"));
  const auto summary_of_fleet = summarize_fleet(sensors);
  const auto doc = fleet_document(sensors, summary_of_fleet);
  const auto& far = doc["sensors"][5];
  EXPECT_EQ(far["flags"], nlohmann::json({"outlier", "datasheet_fail"}));
  EXPECT_NE(far["reasons"][0].get<std::string>().find("N = 0.003 deg/sqrt(s) is an outlier"), std::string::npos)
      << far["reasons"][0];
  EXPECT_NE(far["reasons"][1].get<std::string>().find("+12.5 %"), std::string::npos);
  EXPECT_TRUE(doc["sensors"][6]["flags"].empty()) << doc["sensors"][6]["flags"];
  EXPECT_EQ(doc["sensors"][7]["flags"], nlohmann::json({"error"}));
  EXPECT_TRUE(doc["sensors"][7]["fit"].is_null());
  EXPECT_EQ(doc["sensors"][0]["fit"], nlohmann::json({{"file", "ok1.000000"}}));  // the document, as given
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
  // Q B K R were not fitted: no distribution, no column.
  EXPECT_FALSE(summary["coefficients"].contains("B"));
  const std::string csv = fleet_csv(sensors, summary_of_fleet);
  EXPECT_NE(csv.find("N [deg/sqrt(s)]"), std::string::npos);
  EXPECT_NE(csv.find("bad.txt,error,"), std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
}

TEST(FleetDocument, NoOutlierTestBelowFiveSensors) {
  std::vector<SensorOutcome> sensors{sensor("a", 1e-3, 1e-6), sensor("b", 1.01e-3, 1e-6), sensor("c", 9e-3, 1e-6)};
  const auto doc = fleet_document(sensors, summarize_fleet(sensors));
  EXPECT_TRUE(doc["summary"]["outliers"].empty());
}

TEST(FleetWire, AnOutcomeCrossesRanksExactly) {
  SensorOutcome sent = sensor("b.txt", 1.0e-3 / 3.0, 1e-5, "fail");
  sent.summary->nav = study::NavAtHorizon{3600.0, 58.5, true, "", {{"schuler", 0.1 / 7.0, 1234.5, NAN}}};
  const std::vector<std::string> files{"a.txt", "b.txt"};
  SensorOutcome got;
  EXPECT_EQ(decode_outcome(encode_outcome(1, sent), files, got), 1u);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got.file, "b.txt");
  EXPECT_EQ(got.document, sent.document);
  EXPECT_EQ(got.summary->terms[1].value, sent.summary->terms[1].value);
  EXPECT_EQ(got.summary->datasheet->terms.at(0).verdict, "fail");
  EXPECT_EQ(got.summary->nav->models.at(0).lat_deg, 0.1 / 7.0);
  EXPECT_TRUE(std::isnan(got.summary->nav->models.at(0).lon_deg));
  // Both fleets, from the sent and the received outcomes, are the same document.
  const std::vector<SensorOutcome> a{sent}, b{got};
  EXPECT_EQ(fleet_document(a, summarize_fleet(a)), fleet_document(b, summarize_fleet(b)));

  const SensorOutcome error = failure("a.txt", "a.txt: empty file");
  EXPECT_EQ(decode_outcome(encode_outcome(0, error), files, got), 0u);
  EXPECT_FALSE(got.ok());
  EXPECT_EQ(got.error, "a.txt: empty file");

  auto bytes = encode_outcome(1, sent);
  bytes.resize(bytes.size() - 3);
  EXPECT_THROW(decode_outcome(bytes, files, got), InputError);
  EXPECT_THROW(decode_outcome(encode_outcome(5, sent), files, got), InputError);
}

}  // namespace
}  // namespace imunoise::fleet
