#pragma once
// The report of `imunoise redundant --in-motion ... --report DIR`: each sensor's in-motion curve
// and its static curve on one figure, with both fits, so the inflation a filter should use is
// seen, not only read; the weighted mean level; a table of N, B, K in motion and at rest with
// their ratios; the leakage (in-run calibration) per sensor. Made with the study report's
// machinery (write.hpp, render.hpp, figures.hpp), from the `in_motion` document alone
// (in_motion_json), so the figures cannot disagree with report.json.
#include <string>

#include <nlohmann/json.hpp>

#include "imunoise/study/write.hpp"

namespace imunoise::study {

/// Figures (figures.hpp form) of an `in_motion` document: "in_motion_<i>" per identified sensor
/// (1-based i: points with the intervals of its in-motion curve, its fit's model as a line, and
/// with static recordings the static curve as points and its model dashed: the measured curve
/// and model of the fit document's residuals), then "in_motion_common" (the weighted mean level).
nlohmann::json in_motion_figures(const nlohmann::json& in_motion);

/// report.md of the document (`doc` holds "in_motion" and "figures").
std::string in_motion_markdown(const nlohmann::json& doc);

/// report.html (render.hpp's page pieces; Plotly when `plotly_js` is given, else the SVGs).
std::string in_motion_html(const nlohmann::json& doc, const std::string& plotly_js);

/// Writes report.json (`doc` with "figures" added), report.md, report.html and the figures
/// into `dir` (write_report_files: staged, nothing replaced without options.force).
WrittenReport write_in_motion_report(nlohmann::json doc, const std::string& dir, const WriteOptions& options = {});

}  // namespace imunoise::study
