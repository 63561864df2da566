// The HTML report as a person sees it: rendered by headless Chromium, every figure must be
// drawn with its data points and the page must log no script error. The page writes what it
// drew into DOM attributes (render.hpp), which --dump-dom returns after the scripts ran.
// CI installs chromium (scripts/setup.sh) and sets IMUNOISE_REQUIRE_BROWSER=1 so that a
// missing browser fails there instead of skipping.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"
#include "study_support.hpp"

namespace imunoise {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string browser() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (::access(path, X_OK) == 0) return path;
  }
  return {};
}

// Runs headless Chromium on `html` and returns the DOM after the scripts ran.
std::string dump_dom(const fs::path& html, const fs::path& scratch, std::string* log) {
  const auto profile = scratch / "profile";
  fs::create_directories(profile);
  const auto out = scratch / "dom.html";
  const auto err = scratch / "chromium.log";
  const std::string command =
      browser() +
      " --headless=new --no-sandbox --disable-gpu --no-first-run --disable-background-networking"
      " --disable-component-update --disable-sync --disable-dev-shm-usage"
      " --user-data-dir='" + profile.string() + "' --virtual-time-budget=15000 --dump-dom 'file://" +
      html.string() + "' > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  *log = slurp(err);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << *log;
  return slurp(out);
}

TEST(ReportBrowser, EveryFigureIsDrawnWithDataAndNoScriptError) {
  if (browser().empty()) {
    if (std::getenv("IMUNOISE_REQUIRE_BROWSER") != nullptr) FAIL() << "chromium is required";
    GTEST_SKIP() << "chromium not installed (scripts/setup.sh installs it)";
  }
  if (study::find_plotly_js().empty()) {
    if (std::getenv("IMUNOISE_REQUIRE_BROWSER") != nullptr) FAIL() << "Plotly.js is required";
    GTEST_SKIP() << "Plotly.js not installed (npm ci in web/; scripts/setup.sh does it)";
  }
  const fs::path scratch = fs::temp_directory_path() / ("imunoise-browser-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  std::vector<study::Record> records{
      test::simulated_gyro("gyro_a", 8.9e-4, 1.5e-5, 100.0, 1200.0, 21),
      test::simulated_gyro("gyro_b", 8.6e-4, 1.2e-5, 100.0, 1200.0, 22)};
  study::StudyOptions o;
  o.spec = builtin_spec("tg100");
  const auto doc = study::study_json(study::run_study(std::move(records), o));
  const auto written = study::write_report(doc, (scratch / "report").string());
  ASSERT_TRUE(written.interactive);
  std::string log;
  const std::string dom = dump_dom(scratch / "report" / "report.html", scratch, &log);
  ASSERT_NE(dom.find("<body"), std::string::npos) << log;
  EXPECT_NE(dom.find("data-errors=\"0\""), std::string::npos) << "script errors; log:\n" << log;
  const std::size_t figures = doc["figures"].size();
  EXPECT_NE(dom.find("data-figures-drawn=\"" + std::to_string(figures) + "\""), std::string::npos)
      << "not every figure was drawn";
  // Each figure: Plotly's SVG with markers for the curve points and the traces of the series.
  for (std::size_t i = 0; i < figures; ++i) {
    const std::regex div("id=\"fig-" + std::to_string(i) + "\"[^>]*");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(dom, m, div)) << "figure " << i;
    std::smatch points;
    const std::string tag = m.str();
    ASSERT_TRUE(std::regex_search(tag, points, std::regex("data-rendered-points=\"(\\d+)\"")))
        << tag;
    std::size_t expected_points = 0;
    for (const auto& s : doc["figures"][i]["series"]) {
      if (s["style"] == "points") expected_points += s["x"].size();
    }
    EXPECT_EQ(std::stoul(points[1]), expected_points) << "figure " << i;
    std::smatch traces;
    ASSERT_TRUE(std::regex_search(tag, traces, std::regex("data-rendered-traces=\"(\\d+)\"")));
    EXPECT_EQ(std::stoul(traces[1]), doc["figures"][i]["series"].size()) << "figure " << i;
  }
  EXPECT_NE(dom.find("class=\"main-svg\""), std::string::npos);
  fs::remove_all(scratch);
}

}  // namespace
}  // namespace imunoise
