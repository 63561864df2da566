#pragma once
// Writes a study's report directory: report.json (the document), report.html, report.md, CSV
// tables, the Kalibr imu.yaml and every figure as SVG and PNG (gnuplot). Nothing the user has
// is replaced without `force`; everything is written under a staging name inside DIR and
// renamed into place at the end (report.html and report.json last), so an interrupted run
// never leaves a report that looks complete.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace imunoise::study {

struct WriteOptions {
  bool force = false;          ///< replace existing report files
  std::string plotly_js_path;  ///< plotly-basic.min.js ("": find_plotly_js())
  std::string gnuplot = "gnuplot";  ///< gnuplot executable ("": no static figures)
};

struct WrittenReport {
  std::string dir;
  std::vector<std::string> files;   ///< paths written, relative to dir
  std::vector<std::string> notes;   ///< what was left out and why (no gnuplot, no Plotly)
  bool interactive = false;         ///< report.html has the Plotly figures
};

/// Where Plotly.js is: $IMUNOISE_PLOTLY_JS, else the repository's web/node_modules (npm ci in
/// web/), else the installed share/imunoise copy; "" when none exists.
std::string find_plotly_js();

/// The check write_report makes first, for callers to make before the study's work: InputError
/// when `dir` exists but is not a directory, or (without force) already holds a report
/// (report.json, report.html or report.md). write_report still checks every file it writes.
void check_report_dir(const std::string& dir, bool force);

/// Writes the report of `doc` (study_json) into `dir` (created when missing). InputError when
/// DIR cannot be created or written, or a report file exists without force (naming it).
WrittenReport write_report(const nlohmann::json& doc, const std::string& dir,
                           const WriteOptions& options = {});

/// The writer behind write_report, for every report made with this machinery (the fleet's,
/// fleet/report.hpp): `texts` by path relative to DIR, report.html made by `html` from the
/// Plotly.js text ("" when Plotly.js is missing: the page shows the SVGs), the figures of
/// `figures` (figures.hpp) drawn by gnuplot into figures/. The same checks, staging and order
/// as write_report (report.html, then report.json when in `texts`, last).
using HtmlRenderer = std::function<std::string(const std::string& plotly_js)>;
WrittenReport write_report_files(std::map<std::string, std::string> texts, const HtmlRenderer& html,
                                 const nlohmann::json& figures, const std::string& dir,
                                 const WriteOptions& options = {});

}  // namespace imunoise::study
