#pragma once
// The report's figures as data: each figure is a plain JSON description (title, axis labels
// with units, log axes, series of points with confidence bars, lines, dashed asymptotes with
// labels, datasheet limits), derived from the report document. Both renderers draw exactly
// this: Plotly.js in report.html (render.hpp) and gnuplot for the SVG/PNG files (gnuplot.hpp).
//
// Figure: {"id", "title", "caption", "x_label", "y_label", "x_log", "y_log", "series": [...]}
// Series: {"name", "style": "points" | "line" | "dashed" | "limit", "color": index,
//          "x": [...], "y": [...], optional "y_low"/"y_high" (confidence bars),
//          optional "label": {"x", "y", "text"} (text written next to the series)}.
#include <nlohmann/json.hpp>

namespace imunoise::study {

/// Figures of a study document (study_json without "figures"): all channels' Allan
/// deviations overlaid per quantity, one figure per channel with its fitted model, term
/// asymptotes and datasheet limits, extra estimators, navigation error per model, fused axes.
nlohmann::json build_figures(const nlohmann::json& doc);

/// The colour palette shared by both renderers (hex "#rrggbb"), indexed modulo its size.
const char* palette_color(int index);

}  // namespace imunoise::study
