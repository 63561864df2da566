#pragma once
// The fleet report: report.html, report.md and figures/ written from the fleet document
// (fleet.hpp) with the study report's machinery (study/figures.hpp descriptions, the page,
// style and Plotly script of study/render.hpp, gnuplot and the staged writing of
// study/write.hpp), so a fleet report and a study report look and behave alike.
//
// Figures:
//  - fleet_adev: every sensor's oadev curve (the fit's octave points) overlaid, the typical
//    sensors in grey, the outliers each in a colour with its fitted model and named in the
//    legend, the datasheet limits (spec x (1 + tolerance)) as dotted lines; hovering a point
//    names its sensor;
//  - fleet_<T> for each coefficient T in Q N B K R with identified values: a strip plot of
//    the identified values over the sensors (x = the sensor's place in the file list, its
//    confidence interval as a bar, outliers in colour), the 5/25/50/75/95 % points as lines and
//    as a box beside the strip, and the datasheet limit when a spec was given;
//  - fleet_nav (fleet --nav): the distribution of the sensors' navigation errors.
// Tables: coefficient distributions, datasheet pass rate with per-term verdict counts, the
// flagged sensors with their reasons, the failed files.
//
// Deterministic: everything depends only on the fleet document, so a parallel run (whose
// fleet.json is the serial run's bytes) writes the serial run's report.
#include <string>

#include <nlohmann/json.hpp>

#include "imunoise/study/write.hpp"

namespace imunoise::fleet {

/// The report's figures (study/figures.hpp descriptions) for a fleet document.
nlohmann::json fleet_figures(const nlohmann::json& fleet);

/// report.md: summary, coefficient distributions, pass rate, flagged sensors, failed files,
/// figures (figures/<id>.svg), notes. `figures`: fleet_figures(fleet).
std::string fleet_markdown(const nlohmann::json& fleet, const nlohmann::json& figures,
                           const std::string& title);

/// report.html: the same content in the study report's page, figures drawn by Plotly.js
/// (interactive) when `plotly_js` is given, else the static SVGs.
std::string fleet_html(const nlohmann::json& fleet, const nlohmann::json& figures,
                       const std::string& title, const std::string& plotly_js);

/// Writes report.html, report.md and figures/*.svg|png into `dir` (study::write_report_files:
/// nothing replaced without options.force, staged, report.html last).
study::WrittenReport write_fleet_report(const nlohmann::json& fleet, const std::string& dir,
                                        const study::WriteOptions& options = {},
                                        const std::string& title = "imunoise fleet report");

/// Checks before any work that the fleet's outputs (DIR/fleet.json, fleet.csv and the report)
/// can be written, and creates DIR. InputError naming the path when DIR is a file, an output
/// exists without `force`, or DIR cannot be created.
void prepare_output_dir(const std::string& dir, bool force);

}  // namespace imunoise::fleet
