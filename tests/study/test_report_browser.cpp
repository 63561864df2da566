// The HTML report as a person sees it: rendered by headless Chromium, every figure must be
// drawn with its data points and the page must log no script error (browser_support.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"
#include "study/browser_support.hpp"
#include "study_support.hpp"

namespace imunoise {
namespace {

namespace fs = std::filesystem;

TEST(ReportBrowser, EveryFigureIsDrawnWithDataAndNoScriptError) {
  IMUNOISE_REQUIRE_BROWSER_OR_SKIP();
  const fs::path scratch = fs::temp_directory_path() / ("imunoise-browser-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  std::vector<study::Record> records{
      test::simulated_gyro("gyro_a", 8.9e-4, 1.5e-5, 100.0, 1200.0, 21),
      test::simulated_gyro("gyro_b", 8.6e-4, 1.2e-5, 100.0, 1200.0, 22)};
  // gyro_a with its dynamic Allan variance: the heat map is drawn too.
  std::vector<double> rate(records[0].phase_si.size() - 1);
  for (std::size_t i = 0; i < rate.size(); ++i) {
    rate[i] = (records[0].phase_si[i + 1] - records[0].phase_si[i]) * records[0].rate_hz;
  }
  records[0].davar = preprocess::dynamic_allan(rate, records[0].rate_hz, {60.0, 30.0});
  study::StudyOptions o;
  o.spec = builtin_spec("tg100");
  const auto doc = study::study_json(study::run_study(std::move(records), o));
  const auto written = study::write_report(doc, (scratch / "report").string());
  ASSERT_TRUE(written.interactive);
  std::string log;
  const std::string dom = test::dump_dom(scratch / "report" / "report.html", scratch, &log);
  bool heat_map = false;
  for (const auto& f : doc["figures"]) heat_map = heat_map || f["id"] == "davar_gyro_a";
  EXPECT_TRUE(heat_map);
  test::expect_every_figure_drawn(dom, doc["figures"], log);
  fs::remove_all(scratch);
}

// A gmwm study of a record with two Gauss-Markov terms (the sum of two simulator channels): the
// channel's figure draws each term's curve (GM1, GM2) and the page still renders without error.
TEST(ReportBrowser, GmwmFigureDrawsEveryGaussMarkovTerm) {
  IMUNOISE_REQUIRE_BROWSER_OR_SKIP();
  const fs::path scratch = fs::temp_directory_path() / ("imunoise-browser-gm-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  const double rate_hz = 100.0;
  const std::size_t n = 360000;  // 1 h
  sim::NoiseModel fast, slow;
  fast.n_unit_sqrt_s = 1e-3;
  fast.gm_sigma_unit = 5e-3;
  fast.gm_time_s = 1.0;
  slow.gm_sigma_unit = 2e-3;
  slow.gm_time_s = 60.0;
  auto y = sim::simulate(fast, rate_hz, n, 41);
  const auto y2 = sim::simulate(slow, rate_hz, n, 42);
  const double to_si = parse_unit("deg/s").to_si;
  for (std::size_t i = 0; i < n; ++i) y[i] = (y[i] + y2[i]) * to_si;
  study::Record r;
  r.name = "gyro_gm";
  r.source = "gyro_gm.csv";
  r.rate_hz = rate_hz;
  r.n_samples = n;
  r.phase_si = phase_from_rate(y, 1.0 / rate_hz, compensated_mean(y));
  r.rate_unit = parse_unit("deg/s");
  r.unit_given = true;
  std::vector<study::Record> records;
  records.push_back(std::move(r));
  study::StudyOptions o;
  o.fit.method = fit::Method::gmwm;
  fit::parse_gmwm_terms("N,GM,GM", o.fit.gmwm);
  const auto doc = study::study_json(study::run_study(std::move(records), o));
  const auto& model = doc["channels"][0]["model"];
  int gm_curves = 0;
  for (const auto& t : model["terms"]) gm_curves += t["symbol"].get<std::string>().rfind("GM", 0) == 0;
  EXPECT_EQ(gm_curves, 2) << model["terms"].dump();
  // The report's imu.yaml says what Kalibr cannot carry.
  ASSERT_EQ(doc["kalibr"]["not_carried"].size(), 1u) << doc["kalibr"];
  EXPECT_NE(doc["kalibr"]["text"].get<std::string>().find("2 Gauss-Markov terms"), std::string::npos);
  const auto written = study::write_report(doc, (scratch / "report").string());
  ASSERT_TRUE(written.interactive);
  std::string log;
  const std::string dom = test::dump_dom(scratch / "report" / "report.html", scratch, &log);
  test::expect_every_figure_drawn(dom, doc["figures"], log);
  // The channel's figure has a series per GM term, labelled with its sigma and T_c.
  bool labelled = false;
  for (const auto& f : doc["figures"]) {
    if (f["id"] != "adev_gyro_gm") continue;
    for (const auto& s : f["series"]) labelled = labelled || (s.contains("name") && s["name"].is_string() && s["name"].get<std::string>().rfind("GM2:", 0) == 0);
  }
  EXPECT_TRUE(labelled);
  fs::remove_all(scratch);
}

}  // namespace
}  // namespace imunoise
