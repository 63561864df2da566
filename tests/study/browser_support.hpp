#pragma once
// Headless Chromium for the report tests (study and fleet reports): the page writes what it
// drew into DOM attributes (study/render.hpp), which --dump-dom returns after the scripts ran.
// CI installs chromium (scripts/setup.sh) and sets IMUNOISE_REQUIRE_BROWSER=1 so that a
// missing browser or Plotly.js fails there instead of skipping.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "imunoise/study/write.hpp"

namespace imunoise::test {

inline std::string slurp_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string browser() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (::access(path, X_OK) == 0) return path;
  }
  return {};
}

/// Empty when the browser test can run; else why not (the caller skips, or fails when
/// IMUNOISE_REQUIRE_BROWSER is set).
inline std::string browser_missing() {
  if (browser().empty()) return "chromium not installed (scripts/setup.sh installs it)";
  if (study::find_plotly_js().empty()) return "Plotly.js not installed (npm ci in web/; scripts/setup.sh does it)";
  return {};
}

#define IMUNOISE_REQUIRE_BROWSER_OR_SKIP()                                                  \
  if (const std::string why = ::imunoise::test::browser_missing(); !why.empty()) {         \
    if (std::getenv("IMUNOISE_REQUIRE_BROWSER") != nullptr) FAIL() << why << " (required)"; \
    GTEST_SKIP() << why;                                                                    \
  }

/// Runs headless Chromium on `html` and returns the DOM after the scripts ran.
inline std::string dump_dom(const std::filesystem::path& html, const std::filesystem::path& scratch,
                            std::string* log) {
  const auto profile = scratch / "profile";
  std::filesystem::create_directories(profile);
  const auto out = scratch / "dom.html";
  const auto err = scratch / "chromium.log";
  const std::string command =
      browser() +
      " --headless=new --no-sandbox --disable-gpu --no-first-run --disable-background-networking"
      " --disable-component-update --disable-sync --disable-dev-shm-usage"
      " --user-data-dir='" + profile.string() + "' --virtual-time-budget=15000 --dump-dom 'file://" +
      html.string() + "' > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  *log = slurp_file(err);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << *log;
  return slurp_file(out);
}

/// Points a figure should show as markers: every point of a "points" series, every cell of a
/// "heatmap" (its hover trace).
inline std::size_t expected_markers(const nlohmann::json& figure) {
  std::size_t n = 0;
  for (const auto& s : figure["series"]) {
    if (s["style"] == "points") n += s["x"].size();
    if (s["style"] == "heatmap") n += s["z"].size();
  }
  return n;
}

/// The page logged no script error, drew every figure of `figures`, each with its markers and
/// one trace per series.
inline void expect_every_figure_drawn(const std::string& dom, const nlohmann::json& figures,
                                      const std::string& log) {
  ASSERT_NE(dom.find("<body"), std::string::npos) << log;
  EXPECT_NE(dom.find("data-errors=\"0\""), std::string::npos) << "script errors; log:\n" << log;
  EXPECT_NE(dom.find("data-figures-drawn=\"" + std::to_string(figures.size()) + "\""), std::string::npos)
      << "not every figure was drawn";
  for (std::size_t i = 0; i < figures.size(); ++i) {
    const std::regex div("id=\"fig-" + std::to_string(i) + "\"[^>]*");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(dom, m, div)) << "figure " << i;
    const std::string tag = m.str();
    std::smatch points;
    ASSERT_TRUE(std::regex_search(tag, points, std::regex("data-rendered-points=\"(\\d+)\""))) << tag;
    EXPECT_EQ(std::stoul(points[1]), expected_markers(figures[i])) << "figure " << i;
    std::smatch traces;
    ASSERT_TRUE(std::regex_search(tag, traces, std::regex("data-rendered-traces=\"(\\d+)\"")));
    EXPECT_EQ(std::stoul(traces[1]), figures[i]["series"].size()) << "figure " << i;
    // Heat maps: one shape per cell, every one inside the axes (the cells tile the ranges).
    std::size_t cells = 0;
    for (const auto& s : figures[i]["series"]) cells += s["style"] == "heatmap" ? s["z"].size() : 0;
    std::smatch shapes, outside;
    ASSERT_TRUE(std::regex_search(tag, shapes, std::regex("data-rendered-shapes=\"(\\d+)\"")));
    EXPECT_EQ(std::stoul(shapes[1]), cells) << "figure " << i;
    ASSERT_TRUE(std::regex_search(tag, outside, std::regex("data-shapes-outside=\"(\\d+)\"")));
    EXPECT_EQ(std::stoul(outside[1]), 0u) << "figure " << i << ": heat-map cells outside the axes";
  }
  EXPECT_NE(dom.find("class=\"main-svg\""), std::string::npos);
}

}  // namespace imunoise::test
