#pragma once
// Renderers of the study document (study_json): every output of `imunoise analyze` is made
// from the same document, so the HTML, Markdown, CSV and figures cannot disagree with
// report.json.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace imunoise::study {

/// report.md: inputs, noise terms with intervals (record and customary units), datasheet
/// verdicts, notes and links to the figures (figures/<id>.svg).
std::string render_markdown(const nlohmann::json& doc);

/// report.html: one self-contained page. With `plotly_js` (the text of plotly-basic.min.js)
/// the figures are interactive Plotly charts drawn from the document embedded in the page, so
/// it opens offline; without it the page shows the static SVG figures (figures/<id>.svg).
/// The page records its own script errors and the points drawn per figure in DOM attributes
/// (data-rendered-points on each figure, data-errors on <body>) for headless checks.
std::string render_html(const nlohmann::json& doc, const std::string& plotly_js);

/// The pieces of every report page (the study's and the fleet's, fleet/report.hpp), so that
/// all reports share one style, one figure grid and one Plotly script:
/// html_page_head: doctype, style, Plotly.js when given, <body> and the <header> with the
/// title (the caller adds the subtitle, closes </header> and opens <main>);
/// html_figures: the figure grid (interactive divs or the static SVGs; a figure with
/// "wide": true spans the grid like the study's first overlay);
/// html_page_tail: closes <main>, embeds `doc` (which must hold "figures") and the script that
/// draws them, closes the page.
std::string html_page_head(const std::string& title, const std::string& plotly_js);
std::string html_figures(const nlohmann::json& figures, bool interactive);
std::string html_page_tail(const nlohmann::json& doc, bool interactive);

/// The "## Figures" section of report.md (links to figures/<id>.svg and .png).
std::string markdown_figures(const nlohmann::json& figures);

/// Text escaped for HTML (& < > ").
std::string html_escape_text(const std::string& s);

/// CSV tables by file name: curves.csv (every curve point of every channel),
/// coefficients.csv (the fitted terms), spec_comparison.csv (when a datasheet was given).
std::map<std::string, std::string> render_csv_tables(const nlohmann::json& doc);

/// A gnuplot script drawing one figure (figures.hpp) to `svg_path` (svg terminal) and
/// `png_path` (pngcairo terminal), data inline.
std::string gnuplot_script(const nlohmann::json& figure, const std::string& svg_path,
                           const std::string& png_path);

/// A file-name-safe version of a figure id (letters, digits, '-', '_').
std::string file_stem(const std::string& id);

}  // namespace imunoise::study
