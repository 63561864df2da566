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

}  // namespace
}  // namespace imunoise
