#include "imunoise/study/in_motion_report.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "imunoise/study/render.hpp"

namespace imunoise::study {
namespace {

using nlohmann::json;

std::string str(const json& j) { return j.is_string() ? j.get<std::string>() : j.dump(); }

bool positive(const json& v) { return v.is_number() && v.get<double>() > 0.0; }

// The in-motion curve as points with their intervals.
json curve_series(const json& points, const std::string& name, int color) {
  json x = json::array(), y = json::array(), lo = json::array(), hi = json::array();
  for (const auto& p : points) {
    if (!positive(p["adev"])) continue;
    x.push_back(p["tau_s"]);
    y.push_back(p["adev"]);
    lo.push_back(p["ci_low"]);
    hi.push_back(p["ci_high"]);
  }
  return {{"name", name}, {"style", "points"}, {"color", color}, {"x", x}, {"y", y}, {"y_low", lo}, {"y_high", hi}};
}

// A fit document's measured curve ("adev") or model ("adev_model") over the taus it used.
json fit_series(const json& fit, const char* key, const std::string& name, const char* style, int color) {
  json x = json::array(), y = json::array();
  if (fit.is_object() && fit.contains("diagnostics")) {
    for (const auto& r : fit["diagnostics"]["residuals"]) {
      if (!positive(r[key])) continue;
      x.push_back(r["tau_s"]);
      y.push_back(r[key]);
    }
  }
  return {{"name", name}, {"style", style}, {"color", color}, {"x", x}, {"y", y}};
}

std::string term_text(const json& fit, const char* term) {
  if (!fit.is_object() || !fit.contains("terms") || !fit["terms"].contains(term)) return "-";
  const auto& t = fit["terms"][term];
  if (!t.value("identified", false)) return "not identified";
  return fmt::format("{:.4g} [{:.4g}, {:.4g}]", t["value"].get<double>(), t["ci_low"].get<double>(),
                     t["ci_high"].get<double>());
}

std::string ratio_text(const json& sensor, const char* term) {
  if (!sensor.contains("inflation") || !sensor["inflation"].contains(term)) return "-";
  const auto& r = sensor["inflation"][term];
  if (r["ratio"].is_null()) return r.value("reason", "not available");
  return fmt::format("{:.3g} [{:.3g}, {:.3g}]", r["ratio"].get<double>(), r["ci_low"].get<double>(),
                     r["ci_high"].get<double>());
}

std::string leakage_text(const json& sensor) {
  if (!sensor.contains("leakage")) return "not removed";
  const auto& l = sensor["leakage"];
  const auto value = [](const json& v) { return v.is_number() ? v.get<double>() : NAN; };
  std::string s = fmt::format("{:.4g} ppm, {:.4g} mrad", value(l["scale_factor_ppm"]), value(l["misalignment_mrad"]));
  if (l.contains("time_offset_ms") && l["time_offset_ms"].is_number()) {
    s += fmt::format(", {:.4g} ms", l["time_offset_ms"].get<double>());
  }
  if (l.contains("g_sensitivity")) {
    const auto& g = l["g_sensitivity"];
    s += fmt::format(", g ({:.3g}, {:.3g}, {:.3g}) {}", g["value"][0].get<double>(), g["value"][1].get<double>(),
                     g["value"][2].get<double>(), str(g["unit"]));
  }
  return s;
}

struct Table {
  std::vector<std::string> head;
  std::vector<std::vector<std::string>> rows;
};

Table sensor_table(const json& im) {
  Table t;
  const bool statics = !im["sensors"].empty() && im["sensors"][0].contains("static_fit");
  t.head = {"sensor", "source", "N in motion", "B in motion", "K in motion"};
  if (statics) {
    for (const char* h : {"N at rest", "N ratio", "B ratio", "K ratio"}) t.head.emplace_back(h);
  }
  t.head.emplace_back("leakage (relative to the unit)");
  for (std::size_t i = 0; i < im["sensors"].size(); ++i) {
    const auto& s = im["sensors"][i];
    std::vector<std::string> row{std::to_string(i + 1), str(s["source"])};
    if (!s.value("identified", false)) {
      for (int c = 0; c < 3; ++c) row.emplace_back("not identified");
      if (statics) {
        for (int c = 0; c < 4; ++c) row.emplace_back("-");
      }
    } else {
      const json fit = s.contains("fit") ? s["fit"] : json();
      for (const char* term : {"N", "B", "K"}) row.push_back(term_text(fit, term));
      if (statics) {
        row.push_back(term_text(s.value("static_fit", json()), "N"));
        for (const char* term : {"N", "B", "K"}) row.push_back(ratio_text(s, term));
      }
    }
    row.push_back(leakage_text(s));
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string summary_line(const json& im) {
  const auto& id = im["identifiability"];
  return fmt::format("geometry {}, {} sensors, {} parity channels, rank {} of {}; {} samples at {:.6g} Hz; deviations "
                     "in {}; {:g} % intervals",
                     str(im["geometry"]), id["sensors"].get<int>(), id["parity_channels"].get<int>(),
                     id["rank"].get<int>(), id["sensors"].get<int>(), im["samples"].get<long long>(),
                     im["rate_hz"].get<double>(), str(im["unit"]), 100.0 * im["ci_level"].get<double>());
}

}  // namespace

json in_motion_figures(const json& im) {
  json figures = json::array();
  const std::string unit = str(im["unit"]);
  const bool statics = !im["sensors"].empty() && im["sensors"][0].contains("static_fit");
  for (std::size_t i = 0; i < im["sensors"].size(); ++i) {
    const auto& s = im["sensors"][i];
    if (!s.value("identified", false)) continue;
    json series = json::array();
    series.push_back(curve_series(s["curve"]["points"], "in motion (parity space)", 0));
    if (s.contains("fit") && s["fit"].is_object()) {
      series.push_back(fit_series(s["fit"], "adev_model", "in-motion fit", "line", 0));
    }
    if (s.contains("static_fit")) {
      series.push_back(fit_series(s["static_fit"], "adev", "at rest (static recording)", "points", 1));
      series.push_back(fit_series(s["static_fit"], "adev_model", "static fit", "dashed", 1));
    }
    std::string caption = "Points: the sensor's overlapping Allan deviation while the unit moves, from the parity "
                          "space (the N-cornered hat), with its intervals; solid: its noise-model fit.";
    if (statics) {
      caption += " Orange points: the same sensor's static recording; dashed: its fit. The gap between the two is "
                 "the in-motion inflation (the table gives the ratios with intervals).";
    }
    figures.push_back({{"id", fmt::format("in_motion_{}", i + 1)},
                       {"title", fmt::format("Sensor {} ({}): in motion and at rest", i + 1, str(s["source"]))},
                       {"caption", caption},
                       {"x_label", "tau (s)"},
                       {"y_label", "Allan deviation (" + unit + ")"},
                       {"x_log", true},
                       {"y_log", true},
                       {"series", series}});
  }
  json common = curve_series(im["common"]["points"], "weighted mean level sqrt(sum w_i a_i)", 2);
  figures.push_back({{"id", "in_motion_common"},
                     {"title", "Weighted mean level of the sensors in motion"},
                     {"caption", str(im["common"]["description"])},
                     {"x_label", "tau (s)"},
                     {"y_label", "Allan deviation (" + unit + ")"},
                     {"x_log", true},
                     {"y_log", true},
                     {"series", json::array({common})}});
  return figures;
}

std::string in_motion_markdown(const json& doc) {
  const auto& im = doc["in_motion"];
  std::string md = "# In-motion noise of a redundant unit\n\n" + summary_line(im) + ".\n\n";
  if (!im["identifiability"]["per_sensor"].get<bool>()) {
    md += "Per-sensor curves are not identified: " + str(im["identifiability"]["reason"]) + ".\n\n";
  }
  const Table t = sensor_table(im);
  md += "## Sensors\n\nCoefficients in " + str(im["unit"]) + " based units (N unit*sqrt(s), B unit, K unit/sqrt(s)), "
        "with the fit's intervals; ratios in motion / at rest.\n\n|";
  for (const auto& h : t.head) md += " " + h + " |";
  md += "\n|";
  for (std::size_t c = 0; c < t.head.size(); ++c) md += "---|";
  md += "\n";
  for (const auto& row : t.rows) {
    md += "|";
    for (const auto& cell : row) md += " " + cell + " |";
    md += "\n";
  }
  md += "\n" + markdown_figures(doc["figures"]);
  if (!im["notes"].empty()) {
    md += "\n## Notes\n\n";
    for (const auto& n : im["notes"]) md += "- " + str(n) + "\n";
  }
  return md;
}

std::string in_motion_html(const json& doc, const std::string& plotly_js) {
  const auto& im = doc["in_motion"];
  const bool interactive = !plotly_js.empty();
  const std::string title = "In-motion noise of a redundant unit (" + str(im["geometry"]) + ")";
  std::string h = html_page_head(title, plotly_js);
  h += "<div class=\"sub\">" + html_escape_text(summary_line(im)) + "</div></header>\n<main>\n";
  if (!im["identifiability"]["per_sensor"].get<bool>()) {
    h += "<p><b>Per-sensor curves are not identified:</b> " + html_escape_text(str(im["identifiability"]["reason"])) +
         "</p>\n";
  }
  h += html_figures(doc["figures"], interactive);
  const Table t = sensor_table(im);
  h += "<h2>Sensors</h2>\n<p class=\"soft\">Coefficients in " + html_escape_text(str(im["unit"])) +
       " based units (N unit*sqrt(s), B unit, K unit/sqrt(s)) with the fit's intervals; ratios in motion / at "
       "rest.</p>\n<table><thead><tr>";
  for (const auto& c : t.head) h += "<th>" + html_escape_text(c) + "</th>";
  h += "</tr></thead><tbody>";
  for (const auto& row : t.rows) {
    h += "<tr>";
    for (const auto& c : row) h += "<td>" + html_escape_text(c) + "</td>";
    h += "</tr>";
  }
  h += "</tbody></table>\n";
  if (!im["notes"].empty()) {
    std::string list;
    for (const auto& n : im["notes"]) list += "<li>" + html_escape_text(str(n)) + "</li>";
    h += "<h2>Notes</h2>\n<ul class=\"notes\">" + list + "</ul>\n";
  }
  h += html_page_tail({{"title", title}, {"figures", doc["figures"]}}, interactive);
  return h;
}

WrittenReport write_in_motion_report(json doc, const std::string& dir, const WriteOptions& options) {
  doc["figures"] = in_motion_figures(doc["in_motion"]);
  std::map<std::string, std::string> texts;
  texts["report.json"] = doc.dump(1) + "\n";
  texts["report.md"] = in_motion_markdown(doc);
  return write_report_files(
      std::move(texts), [&](const std::string& plotly) { return in_motion_html(doc, plotly); }, doc["figures"], dir,
      options);
}

}  // namespace imunoise::study
