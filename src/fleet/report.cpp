#include "imunoise/fleet/report.hpp"
#include "imunoise/error.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include <fmt/core.h>

#include "imunoise/study/render.hpp"
#include "imunoise/study/study.hpp"

namespace imunoise::fleet {
namespace {

using json = nlohmann::json;

const char* const kTerms[] = {"Q", "N", "B", "K", "R"};
constexpr const char* kTypicalGrey = "#9aa3b5";
constexpr const char* kQuantileColor = "#444444";

std::string str(const json& v) { return v.is_string() ? v.get<std::string>() : std::string(); }
double num(const json& v) { return v.is_number() ? v.get<double>() : NAN; }
std::string g(const json& v, int digits = 4) {
  return v.is_number() ? fmt::format("{:.{}g}", v.get<double>(), digits) : std::string("–");
}
std::string esc(const std::string& s) { return study::html_escape_text(s); }
std::string md_esc(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

bool has_flag(const json& sensor, const std::string& flag) {
  for (const auto& f : sensor["flags"]) {
    if (f == flag) return true;
  }
  return false;
}

// The name a sensor goes by in legends and tables: its file name, or the path as given when
// two files share a name.
std::vector<std::string> sensor_names(const json& fleet) {
  std::vector<std::string> names;
  std::map<std::string, int> count;
  for (const auto& s : fleet["sensors"]) {
    names.push_back(std::filesystem::path(str(s["file"])).filename().string());
    ++count[names.back()];
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (count[names[i]] > 1) names[i] = str(fleet["sensors"][i]["file"]);
  }
  return names;
}

// A coefficient's datasheet limit in the records' unit: spec x (1 + tolerance) from the
// comparison of a sensor that measured it (measured value in the record's unit over the same
// value in the datasheet's unit gives the conversion). NaN when no sensor has it.
struct Limit {
  double value = NAN;  ///< in the records' unit
  std::string text;    ///< "datasheet N 0.05 deg/sqrt(h)"
};

Limit datasheet_limit(const json& fleet, const std::string& term, const std::string& unit) {
  Limit limit;
  for (const auto& s : fleet["sensors"]) {
    const auto& fit = s["fit"];
    if (fit.is_null() || !fit.contains("spec_comparison") || fit["spec_comparison"].is_null()) continue;
    if (!fit["terms"].contains(term) || str(fit["terms"][term]["unit"]) != unit) continue;
    const double value = num(fit["terms"][term]["value"]);
    for (const auto& t : fit["spec_comparison"]["terms"]) {
      if (str(t["symbol"]) != term || !t.contains("spec") || !t.contains("measured_in_spec_unit")) continue;
      const double measured = num(t["measured_in_spec_unit"]["value"]);
      const double spec_limit = num(t["spec"]["limit"]);
      if (!(value > 0.0) || !(measured > 0.0) || !(spec_limit > 0.0)) continue;
      limit.value = spec_limit * value / measured;
      limit.text = fmt::format("datasheet {} {} {}", term, g(t["spec"]["value"]), str(t["spec"]["unit"]));
      if (std::abs(num(t["spec"]["limit"]) - num(t["spec"]["value"])) > 1e-12 * num(t["spec"]["value"])) {
        limit.text += fmt::format(" (limit {} with the tolerance)", g(t["spec"]["limit"]));
      }
      return limit;
    }
  }
  return limit;
}

// The Allan deviation a term's limit allows at tau (paper eq. 5, one term).
double limit_adev(const std::string& term, double value, double tau) {
  if (term == "N") return value / std::sqrt(tau);
  if (term == "B") return std::sqrt(2.0 * std::log(2.0) / std::numbers::pi) * value;
  if (term == "K") return value * std::sqrt(tau / 3.0);
  return NAN;
}

void extend(double& lo, double& hi, double v) {
  if (std::isfinite(v) && v > 0.0) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

// 1. Every sensor's curve overlaid, outliers highlighted and named.
json curves_figure(const json& fleet, const std::vector<std::string>& names) {
  json series = json::array();
  json gx = json::array(), gy = json::array(), gtext = json::array();
  std::string unit;
  double x_lo = INFINITY, x_hi = 0, y_lo = INFINITY, y_hi = 0;
  std::size_t typical = 0;
  int color = 1;
  json highlighted = json::array();
  for (std::size_t i = 0; i < fleet["sensors"].size(); ++i) {
    const auto& s = fleet["sensors"][i];
    const auto& fit = s["fit"];
    if (fit.is_null() || !fit["diagnostics"].contains("residuals")) continue;
    if (unit.empty()) unit = str(fit["unit"]);
    if (str(fit["unit"]) != unit) continue;  // another unit cannot share the axis
    json x = json::array(), y = json::array(), model = json::array();
    for (const auto& p : fit["diagnostics"]["residuals"]) {
      if (!(num(p["adev"]) > 0.0)) continue;
      x.push_back(p["tau_s"]);
      y.push_back(p["adev"]);
      model.push_back(p["adev_model"]);
      extend(x_lo, x_hi, num(p["tau_s"]));
      extend(y_lo, y_hi, num(p["adev"]));
    }
    if (x.empty()) continue;
    if (has_flag(s, "outlier")) {
      std::string why;
      for (const auto& r : s["reasons"]) {
        const std::string reason = str(r);
        if (reason.find("is an outlier") != std::string::npos) {
          why += (why.empty() ? "" : ", ") + reason.substr(0, reason.find(" = "));
        }
      }
      const std::string name = "outlier " + names[i] + " (" + why + ")";
      json text = json::array();
      for (std::size_t k = 0; k < x.size(); ++k) text.push_back(names[i]);
      series.push_back({{"name", name}, {"group", name}, {"style", "points"}, {"color", color},
                        {"x", x}, {"y", y}, {"text", text}});
      series.push_back({{"name", name + " model"}, {"group", name}, {"style", "line"},
                        {"color", color}, {"x", x}, {"y", model}});
      highlighted.push_back(names[i]);
      ++color;
      continue;
    }
    // The typical sensors share one grey trace, each curve separated by a null.
    if (typical > 0) {
      gx.push_back(x.back());
      gy.push_back(nullptr);
      gtext.push_back("");
    }
    for (std::size_t k = 0; k < x.size(); ++k) {
      gx.push_back(x[k]);
      gy.push_back(y[k]);
      gtext.push_back(names[i]);
    }
    ++typical;
  }
  if (typical == 0 && highlighted.empty()) return nullptr;
  json all = json::array();
  if (typical > 0) {
    all.push_back({{"name", fmt::format("{} typical sensors", typical)}, {"style", "line"},
                   {"color", kTypicalGrey}, {"width", 1.2}, {"x", gx}, {"y", gy}, {"text", gtext}});
  }
  for (auto& s : series) all.push_back(std::move(s));
  for (const char* term : {"N", "B", "K"}) {
    const Limit limit = datasheet_limit(fleet, term, [&] {
      // The coefficient's unit as the fits give it.
      for (const auto& s : fleet["sensors"]) {
        if (!s["fit"].is_null() && s["fit"]["terms"].contains(term)) return str(s["fit"]["terms"][term]["unit"]);
      }
      return std::string();
    }());
    if (!std::isfinite(limit.value)) continue;
    json x = json::array(), y = json::array();
    for (int k = 0; k <= 20; ++k) {
      const double tau = x_lo * std::pow(x_hi / x_lo, k / 20.0);
      x.push_back(tau);
      y.push_back(limit_adev(term, limit.value, tau));
    }
    all.push_back({{"name", limit.text}, {"style", "limit"}, {"color", 6}, {"x", x}, {"y", y}});
  }
  json figure{{"id", "fleet_adev"},
              {"title", "Allan deviation of every sensor"},
              {"caption", fmt::format("Overlapping Allan deviation of each sensor at the fit's "
                                      "taus: grey, the {} typical sensors; in colour, each "
                                      "outlier ({} of them, named in the legend with the "
                                      "coefficients that make it one) with its fitted model; "
                                      "black dotted: datasheet limits. Hover a curve to see "
                                      "its sensor.",
                                      typical, highlighted.size())},
              {"x_label", "averaging time tau [s]"},
              {"y_label", "Allan deviation [" + unit + "]"},
              {"x_log", true},
              {"y_log", true},
              {"wide", true},
              {"series", std::move(all)}};
  if (x_hi > x_lo && y_hi > y_lo) {
    figure["x_range"] = {x_lo / 1.5, x_hi * 1.5};
    figure["y_range"] = {y_lo / 2.0, y_hi * 1.6};
  }
  return figure;
}

// The fits' confidence level in percent ("95").
std::string fit_level_percent(const json& fleet) {
  for (const auto& s : fleet["sensors"]) {
    if (!s["fit"].is_null() && s["fit"].contains("level")) return fmt::format("{:g}", 100.0 * num(s["fit"]["level"]));
  }
  return "–";
}

// Lines at the distribution's quantiles across the strip, and a box-and-whisker beside it.
void quantile_series(const json& d, double x0, double x1, double box_x, double box_w, json& series) {
  const auto hline = [&](const char* name, const char* group, const char* style, double y) {
    json s{{"name", name}, {"style", style}, {"color", kQuantileColor}, {"width", 1.2},
           {"x", {x0, x1}}, {"y", {y, y}}};
    if (group != nullptr) s["group"] = group;
    series.push_back(std::move(s));
  };
  hline(fmt::format("median {}", g(d["median"])).c_str(), nullptr, "line", num(d["median"]));
  hline("quartiles (25 %, 75 %)", nullptr, "dashed", num(d["q25"]));
  hline("quartiles (25 %, 75 %) ", "quartiles (25 %, 75 %)", "dashed", num(d["q75"]));
  hline("5 % and 95 % points", nullptr, "limit", num(d["p05"]));
  hline("5 % and 95 % points ", "5 % and 95 % points", "limit", num(d["p95"]));
  // The box: 25-75 % rectangle, median bar, whiskers to the 5 and 95 % points with caps;
  // pieces separated by nulls.
  const double l = box_x - box_w / 2, r = box_x + box_w / 2, cl = box_x - box_w / 4, cr = box_x + box_w / 4;
  const double p05 = num(d["p05"]), q25 = num(d["q25"]), med = num(d["median"]), q75 = num(d["q75"]),
               p95 = num(d["p95"]);
  const json none = nullptr;
  json x = {l, r, r, l, l, l, l, r, r, box_x, box_x, box_x, box_x, box_x, box_x, cl, cr, cr, cl, cr};
  json y = {q25, q25, q75, q75, q25, none, med, med, none, q75, p95, none, q25, p05, none, p95, p95, none, p05, p05};
  series.push_back({{"name", "box: 5, 25, 50, 75, 95 %"}, {"style", "line"}, {"color", kQuantileColor},
                    {"width", 1.6}, {"x", std::move(x)}, {"y", std::move(y)}});
}

// 2. One coefficient over the fleet.
json coefficient_figure(const json& fleet, const std::string& term, const std::vector<std::string>& names) {
  const auto& c = fleet["summary"]["coefficients"][term];
  if (!c.contains("distribution")) return nullptr;
  const std::string unit = str(c["unit"]);
  const auto& d = c["distribution"];
  json tx = json::array(), ty = json::array(), tlo = json::array(), thi = json::array(), tt = json::array();
  json series = json::array();
  double y_lo = INFINITY, y_hi = 0;
  int color = 1;
  const std::size_t n = fleet["sensors"].size();
  json outliers = json::array();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = fleet["sensors"][i];
    const auto& fit = s["fit"];
    if (fit.is_null() || !fit["terms"].contains(term)) continue;
    const auto& t = fit["terms"][term];
    if (!t.value("identified", false) || str(t["unit"]) != unit || !(num(t["value"]) > 0.0)) continue;
    extend(y_lo, y_hi, num(t["value"]));
    extend(y_lo, y_hi, num(t["ci_low"]));
    extend(y_lo, y_hi, num(t["ci_high"]));
    bool outlier_here = false;
    for (const auto& r : s["reasons"]) {
      outlier_here = outlier_here || str(r).rfind(term + " = ", 0) == 0;
    }
    const double x = static_cast<double>(i + 1);
    if (outlier_here) {
      series.push_back({{"name", "outlier " + names[i]}, {"style", "points"}, {"color", color++},
                        {"size", 9}, {"x", {x}}, {"y", {t["value"]}}, {"y_low", {t["ci_low"]}},
                        {"y_high", {t["ci_high"]}}, {"text", {names[i]}}});
      outliers.push_back(names[i]);
      continue;
    }
    tx.push_back(x);
    ty.push_back(t["value"]);
    tlo.push_back(t["ci_low"]);
    thi.push_back(t["ci_high"]);
    tt.push_back(names[i]);
  }
  json all = json::array();
  if (!tx.empty()) {
    all.push_back({{"name", fmt::format("{} sensors", tx.size())}, {"style", "points"}, {"color", 0},
                   {"x", tx}, {"y", ty}, {"y_low", tlo}, {"y_high", thi}, {"text", tt}});
  }
  for (auto& s : series) all.push_back(std::move(s));
  const double box_x = static_cast<double>(n) + 1.0 + std::max(1.0, 0.08 * static_cast<double>(n));
  const double box_w = std::max(0.8, 0.06 * static_cast<double>(n));
  quantile_series(d, 0.5, static_cast<double>(n) + 0.5, box_x, box_w, all);
  const Limit limit = datasheet_limit(fleet, term, unit);
  if (std::isfinite(limit.value)) {
    all.push_back({{"name", limit.text}, {"style", "limit"}, {"color", "#c62828"}, {"width", 2.0},
                   {"x", {0.5, box_x + box_w}}, {"y", {limit.value, limit.value}}});
    extend(y_lo, y_hi, limit.value);
  }
  json figure{{"id", "fleet_" + term},
              {"title", fmt::format("{} over the fleet ({} identified)", term, c["n_identified"].dump())},
              {"caption", fmt::format("Each sensor's identified {} with its {} % confidence "
                                      "interval, at its place in the file list (hover: the sensor); "
                                      "outliers in colour. Lines across and the box on the right: "
                                      "the fleet's median (solid), quartiles (dashed) and 5/95 % "
                                      "points (dotted){}. {} sensors could not identify {}.",
                                      term, fit_level_percent(fleet),
                                      std::isfinite(limit.value) ? "; red dotted: the datasheet limit" : "",
                                      c["n_not_identified"].dump(), term)},
              {"x_label", "sensor (order of the files)"},
              {"y_label", term + " [" + unit + "]"},
              {"x_log", false},
              {"y_log", true},
              {"x_hover", "sensor"},
              {"x_hover_unit", ""},
              {"legend", "outside"},
              {"series", std::move(all)}};
  if (y_hi > 0) {
    const double pad = std::max(1.05, std::pow(y_hi / y_lo, 0.08));
    figure["y_range"] = {y_lo / pad, y_hi * pad};
  }
  figure["x_range"] = {0.0, box_x + box_w};
  return figure;
}

// 3. The navigation error at the horizon of every sensor, per model (fleet --nav).
json nav_figure(const json& fleet, const std::vector<std::string>& names) {
  if (!fleet["summary"].contains("nav")) return nullptr;
  const auto& nav = fleet["summary"]["nav"];
  json series = json::array();
  int color = 0;
  const double n = static_cast<double>(fleet["sensors"].size());
  for (const auto& model : nav["models"]) {
    const std::string name = str(model["model"]);
    json x = json::array(), y = json::array(), text = json::array();
    for (std::size_t i = 0; i < fleet["sensors"].size(); ++i) {
      const auto& fit = fleet["sensors"][i]["fit"];
      if (fit.is_null() || !fit.contains("nav") || !fit["nav"].contains("models")) continue;
      for (const auto& m : fit["nav"]["models"]) {
        if (str(m["model"]) != name || !m["path_m"].is_number()) continue;
        x.push_back(static_cast<double>(i + 1));
        y.push_back(num(m["path_m"]) / 1000.0);
        text.push_back(names[i]);
      }
    }
    if (x.empty() || model["path_m"].is_null()) {
      ++color;
      continue;
    }
    series.push_back({{"name", name}, {"group", name}, {"style", "points"}, {"color", color},
                      {"x", std::move(x)}, {"y", std::move(y)}, {"text", std::move(text)}});
    const double median_km = num(model["path_m"]["median"]) / 1000.0;
    series.push_back({{"name", name + " median " + fmt::format("{:.4g}", median_km) + " km"},
                      {"group", name}, {"style", "dashed"}, {"color", color},
                      {"x", {0.5, n + 0.5}}, {"y", {median_km, median_km}}});
    ++color;
  }
  if (series.empty()) return nullptr;
  return {{"id", "fleet_nav"},
          {"title", fmt::format("Position error after {:g} h, every sensor", num(nav["t_s"]) / 3600.0)},
          {"caption", fmt::format("RMS position error along the path of a free-inertial system whose "
                                  "three gyros all have one sensor's fitted noise, at latitude {:g} "
                                  "deg, per navigation model (the study's; dashed: the fleet's median). "
                                  "Hover a point to see its sensor.",
                                  num(nav["latitude_deg"]))},
          {"x_label", "sensor (order of the files)"},
          {"y_label", "path error [km]"},
          {"x_log", false},
          {"y_log", false},
          {"x_hover", "sensor"},
          {"x_hover_unit", ""},
          {"legend", "outside"},
          {"series", std::move(series)}};
}

std::string pass_rate_text(const json& ds) {
  return fmt::format("{} of {} pass {} ({:.1f} %)", ds["n_pass"].dump(), ds["n_judged"].dump(),
                     str(ds["spec"]), 100.0 * num(ds["pass_rate"]));
}

struct Row {
  std::vector<std::string> cells;
};

// The tables both renderers show, as text cells.
struct Tables {
  std::vector<std::string> coefficient_head{"term", "unit", "identified", "not identified", "5 %",
                                            "25 %", "median", "75 %", "95 %"};
  std::vector<Row> coefficients;
  std::vector<std::string> verdict_names;
  std::vector<Row> verdicts;  // term, counts per verdict
  std::vector<Row> flagged;   // sensor, flags, reasons
  std::vector<Row> failed;    // file, error
  std::vector<std::string> nav_head{"model", "sensors", "path 5 % [km]", "25 %", "median", "75 %",
                                    "95 %", "latitude median [deg]", "longitude median [deg]"};
  std::vector<Row> nav;
};

Tables tables(const json& fleet, const std::vector<std::string>& names) {
  Tables t;
  const auto& summary = fleet["summary"];
  for (const char* term : kTerms) {
    if (!summary["coefficients"].contains(term)) continue;
    const auto& c = summary["coefficients"][term];
    Row row{{term, str(c["unit"]), c["n_identified"].dump(), c["n_not_identified"].dump()}};
    for (const char* q : {"p05", "q25", "median", "q75", "p95"}) {
      row.cells.push_back(c.contains("distribution") ? g(c["distribution"][q]) : "–");
    }
    t.coefficients.push_back(std::move(row));
  }
  if (!summary["datasheet"].is_null()) {
    std::set<std::string> verdicts;
    for (const auto& [term, counts] : summary["datasheet"]["terms"].items()) {
      for (const auto& [v, n] : counts.items()) verdicts.insert(v);
    }
    t.verdict_names.assign(verdicts.begin(), verdicts.end());
    for (const auto& [term, counts] : summary["datasheet"]["terms"].items()) {
      Row row{{term}};
      for (const auto& v : t.verdict_names) row.cells.push_back(counts.contains(v) ? counts[v].dump() : "0");
      t.verdicts.push_back(std::move(row));
    }
  }
  for (std::size_t i = 0; i < fleet["sensors"].size(); ++i) {
    const auto& s = fleet["sensors"][i];
    if (s["flags"].empty() || has_flag(s, "error")) continue;
    std::string flags, reasons;
    for (const auto& f : s["flags"]) flags += (flags.empty() ? "" : ", ") + str(f);
    for (const auto& r : s["reasons"]) reasons += (reasons.empty() ? "" : "; ") + str(r);
    t.flagged.push_back({{names[i], flags, reasons}});
  }
  for (const auto& f : summary["failed"]) t.failed.push_back({{str(f["file"]), str(f["error"])}});
  if (summary.contains("nav")) {
    for (const auto& m : summary["nav"]["models"]) {
      Row row{{str(m["model"])}};
      const auto& p = m["path_m"];
      row.cells.push_back(p.is_null() ? "0" : p["n"].dump());
      for (const char* q : {"p05", "q25", "median", "q75", "p95"}) {
        row.cells.push_back(p.is_null() ? "–" : fmt::format("{:.4g}", num(p[q]) / 1000.0));
      }
      row.cells.push_back(m["lat_deg"].is_null() ? "–" : g(m["lat_deg"]["median"]));
      row.cells.push_back(m["lon_deg"].is_null() ? "–" : g(m["lon_deg"]["median"]));
      t.nav.push_back(std::move(row));
    }
  }
  return t;
}

std::string md_table(const std::vector<std::string>& head, const std::vector<Row>& rows) {
  std::string md = "|";
  for (const auto& h : head) md += " " + md_esc(h) + " |";
  md += "\n|";
  for (std::size_t i = 0; i < head.size(); ++i) md += "---|";
  md += "\n";
  for (const auto& r : rows) {
    md += "|";
    for (const auto& c : r.cells) md += " " + md_esc(c) + " |";
    md += "\n";
  }
  return md;
}

std::string html_table(const std::vector<std::string>& head, const std::vector<Row>& rows,
                       std::size_t numeric_from = 99) {
  std::string h = "<table><tr>";
  for (const auto& c : head) h += "<th>" + esc(c) + "</th>";
  h += "</tr>\n";
  for (const auto& r : rows) {
    h += "<tr>";
    for (std::size_t k = 0; k < r.cells.size(); ++k) {
      h += (k >= numeric_from ? "<td class=\"num\">" : "<td>") + esc(r.cells[k]) + "</td>";
    }
    h += "</tr>\n";
  }
  return h + "</table>\n";
}

std::vector<std::string> notes(const json& fleet) {
  const auto& s = fleet["summary"];
  std::vector<std::string> out;
  out.push_back("Outlier rule: " + str(s["outlier_rule"]["score"]) + " (threshold " +
                g(s["outlier_rule"]["threshold"]) + ", at least " + s["outlier_rule"]["min_sensors"].dump() +
                " identified values).");
  out.push_back("Quantiles: " + str(s["quantiles"]) + ".");
  if (!s["datasheet"].is_null()) out.push_back("Pass rule: " + str(s["datasheet"]["rule"]) + ".");
  out.push_back("Every number of this report is in fleet.json (one row a sensor in fleet.csv).");
  return out;
}

std::string nav_heading(const json& fleet) {
  return fmt::format("## Navigation error after {:g} h", num(fleet["summary"]["nav"]["t_s"]) / 3600.0);
}

std::string nav_intro(const json& fleet) {
  const auto& nav = fleet["summary"]["nav"];
  std::string text = fmt::format(
      "RMS errors of a free-inertial system whose three gyros all have one sensor's fitted noise "
      "(the study's navigation models, latitude {:g} deg), over the {} sensors that have it",
      num(nav["latitude_deg"]), nav["n_sensors"].dump());
  if (nav["n_not_computed"].get<int>() > 0) {
    text += fmt::format(" ({} not computed: not an angular rate with a unit)", nav["n_not_computed"].dump());
  }
  return text + ".";
}

std::string summary_line(const json& fleet) {
  const auto& s = fleet["summary"];
  std::string rates;
  for (const auto& r : s["rates_hz"]) rates += (rates.empty() ? "" : ", ") + g(r, 6);
  return fmt::format("{} files, {} analysed, {} failed; sample rates {} Hz; {}; {} outliers, {} "
                     "sensors flagged (failed files included).",
                     s["n_files"].dump(), s["n_analysed"].dump(), s["n_failed"].dump(),
                     rates.empty() ? "–" : rates,
                     s["datasheet"].is_null() ? std::string("no datasheet given")
                                              : pass_rate_text(s["datasheet"]),
                     s["outliers"].size(), s["flagged"].size());
}

}  // namespace

json fleet_figures(const json& fleet) {
  const auto names = sensor_names(fleet);
  json figures = json::array();
  if (auto f = curves_figure(fleet, names); !f.is_null()) figures.push_back(std::move(f));
  for (const char* term : kTerms) {
    if (!fleet["summary"]["coefficients"].contains(term)) continue;
    if (auto f = coefficient_figure(fleet, term, names); !f.is_null()) figures.push_back(std::move(f));
  }
  if (auto f = nav_figure(fleet, names); !f.is_null()) figures.push_back(std::move(f));
  return figures;
}

std::string fleet_markdown(const json& fleet, const json& figures, const std::string& title) {
  const auto names = sensor_names(fleet);
  const Tables t = tables(fleet, names);
  std::string md = fmt::format("# {}\n\nimunoise {} · {}\n\n", title, study::version(), summary_line(fleet));
  md += "## Coefficient distributions\n\nIdentified values only, in the records' unit.\n\n";
  md += md_table(t.coefficient_head, t.coefficients);
  const auto& ds = fleet["summary"]["datasheet"];
  md += "\n## Pass rate\n\n";
  if (ds.is_null()) {
    md += "No datasheet was given (--spec): no pass rate.\n";
  } else {
    md += "**" + pass_rate_text(ds) + "**. Sensors per datasheet term and verdict:\n\n";
    std::vector<std::string> head{"term"};
    head.insert(head.end(), t.verdict_names.begin(), t.verdict_names.end());
    md += md_table(head, t.verdicts);
  }
  md += "\n## Outliers and flagged sensors\n\n";
  if (t.flagged.empty()) {
    md += "No analysed sensor is flagged.\n";
  } else {
    md += md_table({"sensor", "flags", "reasons"}, t.flagged);
  }
  if (!t.failed.empty()) {
    md += "\n## Files that could not be analysed\n\n" + md_table({"file", "error"}, t.failed);
  }
  if (fleet["summary"].contains("nav")) {
    md += "\n" + nav_heading(fleet) + "\n\n" + nav_intro(fleet) + "\n";
    if (!t.nav.empty()) md += "\n" + md_table(t.nav_head, t.nav);
  }
  md += study::markdown_figures(figures);
  md += "## Notes\n\n";
  for (const auto& n : notes(fleet)) md += "- " + n + "\n";
  return md;
}

std::string fleet_html(const json& fleet, const json& figures, const std::string& title,
                       const std::string& plotly_js) {
  const auto names = sensor_names(fleet);
  const Tables t = tables(fleet, names);
  const auto& s = fleet["summary"];
  const bool interactive = !plotly_js.empty();
  std::string h = study::html_page_head(title, plotly_js);
  h += "<div class=\"sub\">imunoise " + esc(std::string(study::version())) + " · " +
       esc(summary_line(fleet)) + "</div></header>\n<main>\n";
  const auto card = [](const std::string& k, const std::string& v) {
    return "<div class=\"card\"><div class=\"k\">" + esc(k) + "</div><div class=\"v\">" + esc(v) + "</div></div>";
  };
  h += "<div class=\"cards\">";
  h += card("sensors analysed", s["n_analysed"].dump() + " / " + s["n_files"].dump());
  if (!s["datasheet"].is_null()) {
    h += card("pass " + str(s["datasheet"]["spec"]),
              fmt::format("{:.1f} %", 100.0 * num(s["datasheet"]["pass_rate"])));
  }
  h += card("outliers", std::to_string(s["outliers"].size()));
  h += card("flagged", std::to_string(s["flagged"].size()));
  h += "</div>\n";
  h += study::html_figures(figures, interactive);
  h += "<h2>Coefficient distributions</h2>\n<p class=\"soft\">Identified values only, in the "
       "records' unit.</p>\n" + html_table(t.coefficient_head, t.coefficients, 2);
  h += "<h2>Pass rate</h2>\n";
  if (s["datasheet"].is_null()) {
    h += "<p class=\"soft\">No datasheet was given (--spec): no pass rate.</p>\n";
  } else {
    std::vector<std::string> head{"term"};
    head.insert(head.end(), t.verdict_names.begin(), t.verdict_names.end());
    h += "<p><b>" + esc(pass_rate_text(s["datasheet"])) + "</b>. Sensors per datasheet term and "
         "verdict:</p>\n" + html_table(head, t.verdicts, 1);
  }
  h += "<h2>Outliers and flagged sensors</h2>\n";
  h += t.flagged.empty() ? std::string("<p class=\"soft\">No analysed sensor is flagged.</p>\n")
                         : html_table({"sensor", "flags", "reasons"}, t.flagged);
  if (!t.failed.empty()) {
    h += "<h2>Files that could not be analysed</h2>\n" + html_table({"file", "error"}, t.failed);
  }
  if (fleet["summary"].contains("nav")) {
    h += "<h2>" + esc(nav_heading(fleet).substr(3)) + "</h2>\n<p class=\"soft\">" + esc(nav_intro(fleet)) +
         "</p>\n" + (t.nav.empty() ? std::string() : html_table(t.nav_head, t.nav, 1));
  }
  std::string list;
  for (const auto& n : notes(fleet)) list += "<li>" + esc(n) + "</li>";
  h += "<h2>Notes</h2>\n<ul class=\"notes\">" + list + "</ul>\n";
  h += study::html_page_tail({{"title", title}, {"figures", figures}}, interactive);
  return h;
}

study::WrittenReport write_fleet_report(const json& fleet, const std::string& dir,
                                        const study::WriteOptions& options, const std::string& title) {
  const json figures = fleet_figures(fleet);
  std::map<std::string, std::string> texts;
  texts["report.md"] = fleet_markdown(fleet, figures, title);
  return study::write_report_files(
      std::move(texts),
      [&](const std::string& plotly) { return fleet_html(fleet, figures, title, plotly); }, figures,
      dir, options);
}

void prepare_output_dir(const std::string& dir, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InputError(dir + ": exists and is not a directory; fix: give -o a directory");
  }
  for (const auto& name : {"fleet.json", "fleet.csv"}) {
    const std::string path = (fs::path(dir) / name).string();
    if (fs::exists(path, ec) && !force) {
      throw InputError(path + ": file exists; imunoise does not overwrite it — choose another -o "
                              "directory or pass --force");
    }
  }
  study::check_report_dir(dir, force);
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create the directory (" + ec.message() + ")");
}

}  // namespace imunoise::fleet
