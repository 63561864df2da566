// Markdown, HTML, CSV and gnuplot renderers of the study document.
#include "imunoise/study/render.hpp"

#include <cmath>

#include <fmt/core.h>

#include "imunoise/study/figures.hpp"

namespace imunoise::study {
namespace {

using json = nlohmann::json;

double num(const json& v) { return v.is_number() ? v.get<double>() : NAN; }

std::string g(const json& v, int digits = 4) {
  return v.is_number() ? fmt::format("{:.{}g}", v.get<double>(), digits) : std::string("–");
}

std::string str(const json& v) { return v.is_string() ? v.get<std::string>() : std::string(); }

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// One sentence on the fault detector's run over the recorded data (redundant unit).
std::string fault_summary(const json& r) {
  if (!r.contains("tests")) return "Fault detection was not run on the recorded data (see the notes).";
  std::string text = fmt::format("Fault detection on the recorded data: {} tests, {} alarms", r["tests"].dump(),
                                 r["alarms"].dump());
  const auto& faults = r["faults"];
  if (faults.empty()) return text + "; no fault detected.";
  text += "; faults:";
  for (const auto& f : faults) {
    if (f["isolated"].get<bool>()) {
      text += fmt::format(" sensor {} from {} s (isolated);", f["sensor"].dump(), g(f["t_s"], 6));
      continue;
    }
    // Not isolable: the fault is on one of the candidates; naming one would accuse it falsely.
    std::string which;
    for (const auto& c : f.value("candidates", json::array())) {
      which += (which.empty() ? "" : ", ") + c.dump();
    }
    text += fmt::format(" on one of sensors {} from {} s (detected, not isolable);", which,
                        g(f["t_s"], 6));
  }
  return text;
}

std::string md_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else out += c;
  }
  return out;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_num(const json& v) {
  return v.is_number() ? fmt::format("{:.10g}", v.get<double>()) : std::string();
}

// The terms shown in tables: the four of the paper, and R when it was fitted.
std::vector<std::string> shown_terms(const json& doc) {
  std::vector<std::string> terms{"N", "B", "K", "Q"};
  for (const auto& ch : doc["channels"]) {
    if (!ch["fit"].is_null() && ch["fit"]["terms"]["R"]["fitted"].get<bool>()) {
      terms.push_back("R");
      break;
    }
  }
  return terms;
}

// A term as the reader wants it: customary unit for a gyro, else the record's unit.
struct TermText {
  std::string value;   // "0.0534"
  std::string ci;      // "[0.0529, 0.0540]"
  std::string unit;
  bool identified = false;
};

TermText term_text(const json& term) {
  const json& t = term.contains("customary") ? term["customary"] : term;
  TermText out;
  out.unit = str(t["unit"]);
  out.identified = term["identified"].get<bool>();
  if (out.identified) {
    out.value = g(t["value"]);
    out.ci = "[" + g(t["ci_low"], 3) + ", " + g(t["ci_high"], 3) + "]";
  } else {
    out.value = t["ci_high"].is_number() ? "< " + g(t["ci_high"], 3) : std::string("–");
    out.ci = "not identified";
  }
  return out;
}

std::string duration_text(double s) {
  if (s >= 3600.0) return fmt::format("{:.3g} h", s / 3600.0);
  if (s >= 60.0) return fmt::format("{:.3g} min", s / 60.0);
  return fmt::format("{:.3g} s", s);
}

std::string quote_gp(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The heat maps' colour scale: viridis at five stops, shared by gnuplot and Plotly.
constexpr std::pair<double, const char*> kHeatScale[] = {
    {0.0, "#440154"}, {0.25, "#3b528b"}, {0.5, "#21918c"}, {0.75, "#5ec962"}, {1.0, "#fde725"}};

std::string heat_scale_js() {
  std::string out = "[";
  for (const auto& [f, c] : kHeatScale) out += fmt::format("{}[{:g},'{}']", out.size() > 1 ? "," : "", f, c);
  return out + "]";
}

std::string series_color(const json& series) {
  return series["color"].is_string() ? series["color"].get<std::string>()
                                     : std::string(palette_color(series["color"].get<int>()));
}

std::string level_text(const json& doc) {
  return fmt::format("{:g} %", 100.0 * doc["options"]["fit_level"].get<double>());
}


// The navigation errors at the end of the run (1 h by default) per channel and model.
struct NavRow {
  std::string channel, model;
  double t_s, lat_deg, path_m, lon_deg;
};

std::vector<NavRow> nav_rows(const json& doc) {
  std::vector<NavRow> rows;
  // Each gyro alone on every axis, then the whole IMU (its gyros and accelerometers on their axes).
  std::vector<std::pair<std::string, const json*>> navs;
  for (const auto& ch : doc["channels"]) {
    if (ch.contains("nav") && !ch["nav"].is_null()) navs.emplace_back(str(ch["name"]), &ch["nav"]);
  }
  if (doc.contains("imu_nav") && !doc["imu_nav"].is_null()) navs.emplace_back("whole IMU", &doc["imu_nav"]["nav"]);
  for (const auto& [name, nav] : navs) {
    for (const auto& m : (*nav)["models"]) {
      const std::size_t last = m["t_s"].size() - 1;
      auto at = [&](const char* key) {
        return m.contains(key) && m[key].is_array() && m[key][last].is_number()
                   ? m[key][last].get<double>() : NAN;
      };
      rows.push_back({name, str(m["model"]), num(m["t_s"][last]), at("lat_deg"), at("path_m"), at("lon_deg")});
    }
  }
  return rows;
}

// One sentence per channel with a dynamic Allan variance: its stationarity verdict.
std::vector<std::pair<std::string, std::string>> davar_lines(const json& doc) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& ch : doc["channels"]) {
    if (!ch.contains("davar") || ch["davar"].is_null()) continue;
    const auto& d = ch["davar"];
    std::string text = fmt::format(
        "{}: {} windows of {} s every {} s at {} taus; {} ({} windows outside the chi-squared band)",
        str(ch["name"]), d["n_windows"].dump(), g(d["window_s"]), g(d["step_s"]), d["tau_s"].size(),
        d["stationary"].get<bool>() ? "stationary" : "NOT stationary", d["n_flagged_windows"].dump());
    std::string changes;
    for (const auto& t : d["change_times_s"]) changes += (changes.empty() ? "" : ", ") + g(t, 5);
    if (!changes.empty()) text += "; changes near t = " + changes + " s";
    if (num(d["suggested_skip_s"]) > 0.0) text += "; suggested --skip " + g(d["suggested_skip_s"], 5) + " s";
    out.emplace_back(str(ch["name"]), text + ".");
  }
  return out;
}

std::string fixed(double v, int digits) {
  return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : std::string("–");
}

// gmwm: a power-law term outside the selected model was not tried (not "not identified").
bool outside_gmwm_model(const json& ch, const std::string& term) {
  if (ch["fit"].is_null() || !ch["fit"].contains("gmwm")) return false;
  const std::string model = "+" + str(ch["fit"]["gmwm"]["model"]) + "+";
  return model.find("+" + term + "+") == std::string::npos;
}

// The correlated and periodic terms (every GM, by correlation time, and the sinusoid) of every
// channel, whatever the method: the power-law table has no column for them.
struct ExtraTermRow {
  std::string channel, term;
  TermText magnitude, shape;
  std::string shape_name;  // "T_c" or "f"
};

std::vector<ExtraTermRow> extra_term_rows(const json& doc) {
  std::vector<ExtraTermRow> rows;
  for (const auto& ch : doc["channels"]) {
    if (ch["fit"].is_null()) continue;
    const auto& terms = ch["fit"]["terms"];
    int index = 0;
    if (terms.contains("GM") && terms["GM"].is_array()) {
      for (const auto& gm : terms["GM"]) {
        rows.push_back({str(ch["name"]), fmt::format("GM{}", ++index), term_text(gm["sigma"]),
                        term_text(gm["correlation_time_s"]), "T_c"});
      }
    }
    if (terms.contains("SIN") && terms["SIN"].is_object() && terms["SIN"].contains("amplitude")) {
      rows.push_back({str(ch["name"]), "SIN", term_text(terms["SIN"]["amplitude"]),
                      term_text(terms["SIN"]["frequency_hz"]), "f"});
    }
  }
  return rows;
}

// gmwm --terms auto: per channel the selected model, its J test and WVIC, and the runner-up
// (the whole candidate table is in report.json, fit.gmwm.candidates).
struct SelectionRow {
  std::string channel, model, j, wvic, runner_up;
  std::size_t candidates = 0;
};

std::vector<SelectionRow> selection_rows(const json& doc) {
  std::vector<SelectionRow> rows;
  for (const auto& ch : doc["channels"]) {
    if (ch["fit"].is_null() || !ch["fit"].contains("gmwm")) continue;
    const auto& gm = ch["fit"]["gmwm"];
    const auto& candidates = gm.value("candidates", json::array());
    SelectionRow row{str(ch["name"]), str(gm["model"]),
                     fmt::format("{} on {} dof (p = {})", g(gm["j_statistic"], 3), gm["dof"].dump(),
                                 g(gm["j_p_value"], 2)),
                     g(gm["wvic"], 5), "–", candidates.size()};
    // Differences within the table, whose criteria share one weight matrix (the selected
    // model's own WVIC above is at its final weight).
    const json* selected = nullptr;
    const json* best_other = nullptr;
    for (const auto& c : candidates) {
      if (c.value("selected", false)) {
        selected = &c;
        continue;
      }
      if (!c.value("converged", false)) continue;
      if (best_other == nullptr || num(c["wvic"]) < num((*best_other)["wvic"])) best_other = &c;
    }
    if (selected != nullptr && best_other != nullptr) {
      row.runner_up = fmt::format("{} (ΔWVIC {:+.3g})", str((*best_other)["model"]),
                                  num((*best_other)["wvic"]) - num((*selected)["wvic"]));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

std::string file_stem(const std::string& id) {
  std::string out;
  for (char c : id) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_';
    out += ok ? c : '_';
  }
  return out.empty() ? std::string("figure") : out;
}

// ---------------------------------------------------------------- Markdown

std::string render_markdown(const json& doc) {
  std::string md = fmt::format("# {}\n\nimunoise {} · {} channel(s)\n\n", str(doc["title"]),
                               str(doc["version"]), doc["channels"].size());
  md += "## Inputs\n\n| channel | source | unit | rate [Hz] | samples | duration | status |\n"
        "|---|---|---|---:|---:|---:|---|\n";
  for (const auto& ch : doc["channels"]) {
    md += fmt::format("| {} | {} | {} | {:g} | {} | {} | {} |\n", md_escape(str(ch["name"])),
                      md_escape(str(ch["source"])), str(ch["unit"]), num(ch["rate_hz"]),
                      ch["n_samples"].get<std::size_t>(), duration_text(num(ch["duration_s"])),
                      ch.contains("error") ? "failed: " + md_escape(str(ch["error"])) : "ok");
  }
  for (const auto& in : doc["inputs"]) {
    if (in["status"] == "unreadable") {
      md += fmt::format("| – | {} | | | | | unreadable: {} |\n", md_escape(str(in["source"])),
                        md_escape(str(in["error"])));
    }
  }
  const auto terms = shown_terms(doc);
  md += fmt::format("\n## Noise model\n\nFit of the paper's eq. 5 to the overlapping Allan "
                    "variance (method {}); values with their {} confidence intervals.\n\n",
                    str(doc["options"]["fit_method"]), level_text(doc));
  md += "| channel |";
  for (const auto& t : terms) md += " " + t + " |";
  md += " chi²/dof |\n|---|";
  for (std::size_t i = 0; i < terms.size(); ++i) md += "---|";
  md += "---:|\n";
  for (const auto& ch : doc["channels"]) {
    if (ch["fit"].is_null()) continue;
    md += "| " + md_escape(str(ch["name"])) + " |";
    for (const auto& t : terms) {
      if (outside_gmwm_model(ch, t)) {
        md += " – (not in the model) |";
        continue;
      }
      const auto tt = term_text(ch["fit"]["terms"][t]);
      md += fmt::format(" {} {} {} |", tt.value, tt.unit, tt.identified ? tt.ci : "(not identified)");
    }
    md += " " + g(ch["fit"]["diagnostics"]["chi2_dof"], 3) + " |\n";
  }
  if (const auto extras = extra_term_rows(doc); !extras.empty()) {
    md += "\nCorrelated and periodic terms (GM: first-order Gauss-Markov sigma and correlation time, by "
          "correlation time; SIN: amplitude and frequency).\n\n| channel | term | magnitude | T_c or f |\n"
          "|---|---|---|---|\n";
    for (const auto& r : extras) {
      md += fmt::format("| {} | {} | {} {} {} | {} = {} {} {} |\n", md_escape(r.channel), r.term, r.magnitude.value,
                        r.magnitude.unit, r.magnitude.identified ? r.magnitude.ci : "(not identified)", r.shape_name,
                        r.shape.value, r.shape.unit, r.shape.identified ? r.shape.ci : "(not identified)");
    }
  }
  if (const auto selection = selection_rows(doc); !selection.empty()) {
    md += "\n### Model selection (gmwm)\n\nThe model of least WVIC (wavelet variance information "
          "criterion) among the candidates; J: the moment conditions' goodness of fit (chi² on its dof "
          "for an exact model). Every candidate is in report.json (fit.gmwm.candidates).\n\n"
          "| channel | model | J | WVIC | next best | candidates |\n|---|---|---|---:|---|---:|\n";
    for (const auto& r : selection) {
      md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", md_escape(r.channel), r.model, r.j, r.wvic,
                        r.runner_up, r.candidates);
    }
  }
  bool any_spec = false;
  for (const auto& ch : doc["channels"]) any_spec = any_spec || !ch["spec_comparison"].is_null();
  if (any_spec) {
    md += fmt::format("\n## Datasheet comparison ({})\n\nPass if measured <= spec x (1 + "
                      "tolerance); conclusive when the whole interval lies on the verdict's "
                      "side.\n\n| channel | term | measured | datasheet | deviation | verdict |\n"
                      "|---|---|---|---|---:|---|\n",
                      str(doc["options"]["spec"]));
    for (const auto& ch : doc["channels"]) {
      const auto& c = ch["spec_comparison"];
      if (c.is_null()) continue;
      for (const auto& t : c["terms"]) {
        const json& m = t.contains("measured_in_spec_unit") ? t["measured_in_spec_unit"]
                                                            : t["measured_customary"];
        std::string verdict = str(t["verdict"]);
        if (verdict == "pass" || verdict == "fail") {
          verdict += t["conclusive"].get<bool>() ? " (conclusive)" : " (inconclusive)";
        }
        md += fmt::format("| {} | {} {} | {} {} | {} | {} | {} |\n", md_escape(str(ch["name"])),
                          str(t["symbol"]), str(t["title"]), g(m["value"]), str(m["unit"]),
                          t.contains("spec") ? g(t["spec"]["value"]) + " " + str(t["spec"]["unit"])
                                             : std::string("–"),
                          t["deviation_percent"].is_number()
                              ? fmt::format("{:+.1f} %", num(t["deviation_percent"]))
                              : std::string("–"),
                          verdict);
      }
    }
  }
  const auto navs = nav_rows(doc);
  if (!navs.empty()) {
    md += fmt::format("\n## Navigation error after {:g} h\n\nRMS errors of a free-inertial "
                      "system whose gyros all have the channel's fitted noise, at latitude "
                      "{:g} deg.\n\n| channel | model | latitude [deg] | path [km] | longitude "
                      "[deg] |\n|---|---|---:|---:|---:|\n",
                      navs.front().t_s / 3600.0, num(doc["options"]["nav_latitude_deg"]));
    for (const auto& r : navs) {
      md += fmt::format("| {} | {} | {} | {} | {} |\n", md_escape(r.channel), r.model,
                        fixed(r.lat_deg, 3), fixed(r.path_m / 1000.0, 3), fixed(r.lon_deg, 3));
    }
  }
  if (const auto davars = davar_lines(doc); !davars.empty()) {
    md += "\n## Stationarity (dynamic Allan variance)\n\n";
    for (const auto& [name, text] : davars) md += "- " + md_escape(text) + "\n";
    md += "\nRule: a window is flagged when its Allan variance at a tau lies outside the chi-squared band "
          "around the median of all windows (Bonferroni over windows and taus).\n";
  }
  if (!doc["redundant"].is_null()) {
    const auto& r = doc["redundant"];
    md += fmt::format("\n## Redundant unit ({})\n\n{} sensors; fused axis gain {} (fused "
                      "noise / one sensor's), GDOP {}; single faults {}detectable, {}isolable.\n",
                      str(r["geometry"]), r["n_sensors"].get<int>(), r["axis_gain"].dump(),
                      g(r["gdop"]), r["detectable"].get<bool>() ? "" : "not ",
                      r["isolable"].get<bool>() ? "" : "not ");
    md += fault_summary(r) + "\n";
  }
  if (doc.contains("reference") && !doc["reference"].is_null()) {
    md += "\n## " + str(doc["reference"]["title"]) + "\n\n" + str(doc["reference"]["markdown"]) + "\n";
  }
  md += markdown_figures(doc["figures"]);
  std::string notes;
  for (const auto& n : doc["notes"]) notes += "- " + str(n) + "\n";
  for (const auto& ch : doc["channels"]) {
    for (const auto& w : ch["warnings"]) notes += "- " + str(ch["name"]) + ": " + str(w) + "\n";
  }
  if (doc["kalibr"]["written"].get<bool>()) {
    notes += "- imu.yaml (Kalibr): " + str(doc["kalibr"]["rule"]) + "\n";
  }
  if (!notes.empty()) md += "## Notes\n\n" + notes;
  return md;
}

// ---------------------------------------------------------------- CSV

std::map<std::string, std::string> render_csv_tables(const json& doc) {
  std::map<std::string, std::string> out;
  std::string curves = "channel,estimator,m,tau_s,dev,unit,n,edf,ci_low,ci_high,alpha\n";
  std::string coefficients =
      "channel,term,value,ci_low,ci_high,unit,identified,customary_value,customary_ci_low,"
      "customary_ci_high,customary_unit,note\n";
  std::string spec = "channel,term,measured,measured_ci_low,measured_ci_high,unit,spec,"
                     "spec_limit,deviation_percent,verdict,ci_vs_limit,conclusive\n";
  bool any_spec = false;
  for (const auto& ch : doc["channels"]) {
    const std::string name = csv_field(str(ch["name"]));
    for (const auto& c : ch["curves"]) {
      for (const auto& p : c["points"]) {
        curves += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", name, str(c["estimator"]),
                              p["m"].get<std::size_t>(), csv_num(p["tau_s"]), csv_num(p["dev"]),
                              csv_field(str(c["unit"])), p["n"].get<std::size_t>(),
                              csv_num(p["edf"]), csv_num(p["ci_low"]), csv_num(p["ci_high"]),
                              p["alpha"].is_number() ? std::to_string(p["alpha"].get<int>())
                                                     : std::string());
      }
    }
    if (!ch["fit"].is_null()) {
      for (const auto& [term, t] : ch["fit"]["terms"].items()) {
        if (!t.contains("value")) continue;  // GM / SIN blocks have their own layout
        const json cust = t.contains("customary") ? t["customary"] : json::object();
        coefficients += fmt::format(
            "{},{},{},{},{},{},{},{},{},{},{},{}\n", name, term, csv_num(t["value"]),
            csv_num(t["ci_low"]), csv_num(t["ci_high"]), csv_field(str(t["unit"])),
            t["identified"].get<bool>() ? "true" : "false",
            cust.contains("value") ? csv_num(cust["value"]) : "",
            cust.contains("ci_low") ? csv_num(cust["ci_low"]) : "",
            cust.contains("ci_high") ? csv_num(cust["ci_high"]) : "",
            cust.contains("unit") ? csv_field(str(cust["unit"])) : "",
            t.contains("note") ? csv_field(str(t["note"])) : "");
      }
    }
    if (!ch["spec_comparison"].is_null()) {
      any_spec = true;
      for (const auto& t : ch["spec_comparison"]["terms"]) {
        const json& m = t.contains("measured_in_spec_unit") ? t["measured_in_spec_unit"]
                                                            : t["measured_customary"];
        spec += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", name, str(t["symbol"]),
                            csv_num(m["value"]), csv_num(m["ci_low"]), csv_num(m["ci_high"]),
                            csv_field(str(m["unit"])),
                            t.contains("spec") ? csv_num(t["spec"]["value"]) : "",
                            t.contains("spec") ? csv_num(t["spec"]["limit"]) : "",
                            csv_num(t["deviation_percent"]), str(t["verdict"]),
                            str(t["ci_vs_limit"]), t["conclusive"].get<bool>() ? "true" : "false");
      }
    }
  }
  out["curves.csv"] = curves;
  out["coefficients.csv"] = coefficients;
  if (any_spec) out["spec_comparison.csv"] = spec;
  return out;
}

// ---------------------------------------------------------------- gnuplot

std::string gnuplot_script(const json& figure, const std::string& svg_path,
                           const std::string& png_path) {
  std::string s = "set encoding utf8\n";
  s += "set terminal svg size 960,640 dynamic enhanced font 'DejaVu Sans,13' background rgb 'white'\n";
  s += "set output " + quote_gp(svg_path) + "\n";
  s += "set title " + quote_gp(str(figure["title"])) + " noenhanced font ',15'\n";
  s += "set xlabel " + quote_gp(str(figure["x_label"])) + " noenhanced\n";
  s += "set ylabel " + quote_gp(str(figure["y_label"])) + " noenhanced\n";
  if (figure["x_log"].get<bool>()) s += "set logscale x\nset format x '10^{%L}'\n";
  if (figure["y_log"].get<bool>()) {
    // Powers of ten, unless the range is narrower than two decades (a fleet's spread).
    const bool narrow = figure.contains("y_range") && num(figure["y_range"][1]) < 100.0 * num(figure["y_range"][0]);
    s += narrow ? "set logscale y\nset format y '%.3g'\n" : "set logscale y\nset format y '10^{%L}'\n";
    if (narrow) {
      // Decade tics alone would leave the axis unlabelled: 1, 2, 3, 5 x 10^k within the range.
      const double lo = num(figure["y_range"][0]), hi = num(figure["y_range"][1]);
      std::string tics;
      for (int k = static_cast<int>(std::floor(std::log10(lo))); k <= static_cast<int>(std::ceil(std::log10(hi))); ++k) {
        for (const double d : {1.0, 2.0, 3.0, 5.0}) {
          const double v = d * std::pow(10.0, k);
          if (v >= lo && v <= hi) tics += fmt::format("{}{:.3g}", tics.empty() ? "" : ", ", v);
        }
      }
      if (!tics.empty()) s += "set ytics (" + tics + ")\n";
    }
  }
  s += "set grid xtics ytics mxtics mytics lc rgb '#d8d8d8' lw 1, lc rgb '#eeeeee' lw 1\n";
  const std::string legend = figure.value("legend", std::string());  // optional key
  s += std::string("set border lc rgb '#444444'\nset key ") +
       (legend == "outside" ? "outside right top" : legend == "below" ? "below horizontal" : "inside left bottom") +
       " noenhanced box lc rgb '#bbbbbb' opaque width 1 spacing 1.1 font ',11'\nset bars small\n";
  if (figure.contains("x_range")) {
    s += fmt::format("set xrange [{:.10g}:{:.10g}]\n", num(figure["x_range"][0]), num(figure["x_range"][1]));
  }
  if (figure.contains("y_range")) {
    s += fmt::format("set yrange [{:.10g}:{:.10g}]\n", num(figure["y_range"][0]), num(figure["y_range"][1]));
  }
  std::string plots;
  int k = 0;
  for (const auto& series : figure["series"]) {
    const std::string block = fmt::format("$d{}", k++);
    s += block + " << EOD\n";
    const auto& x = series["x"];
    const auto& y = series["y"];
    const std::string style = str(series["style"]);
    if (style == "heatmap") {
      // Each cell a filled box coloured by z on a log colour axis.
      const auto& z = series["z"];
      for (std::size_t i = 0; i < z.size(); ++i) {
        s += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", num(x[i]), num(y[i]),
                         num(series["x_low"][i]), num(series["x_high"][i]), num(series["y_low"][i]),
                         num(series["y_high"][i]), num(z[i]));
      }
      s += "EOD\n";
      std::string palette;
      for (const auto& [f, c] : kHeatScale) palette += fmt::format("{}{:g} '{}'", palette.empty() ? "" : ", ", f, c);
      s += "set palette defined (" + palette + ")\nset logscale cb\nset format cb '%.2g'\n";
      s += fmt::format("set cbrange [{:.10g}:{:.10g}]\n", std::pow(10.0, num(series["z_log_range"][0])),
                       std::pow(10.0, num(series["z_log_range"][1])));
      s += "set cblabel " + quote_gp(str(series["z_label"])) + " noenhanced\n";
      plots += (plots.empty() ? "plot " : ", \\\n     ") +
               fmt::format("{} using 1:2:3:4:5:6:7 with boxxyerror fs solid 1.0 noborder fc palette notitle", block);
      continue;
    }
    const bool bars = series.contains("y_low");
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!y[i].is_number()) {
        if (style != "points") s += "\n";  // a null breaks a line into pieces
        continue;
      }
      if (bars) {
        const double yi = num(y[i]);
        const double lo = series["y_low"][i].is_number() ? num(series["y_low"][i]) : yi;
        const double hi = series["y_high"][i].is_number() ? num(series["y_high"][i]) : yi;
        s += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g}\n", num(x[i]), yi, lo, hi);
      } else {
        s += fmt::format("{:.10g} {:.10g}\n", num(x[i]), num(y[i]));
      }
    }
    s += "EOD\n";
    const std::string color = series_color(series);
    // A fitted line grouped with its channel's points shares their key entry.
    const std::string title = series.contains("group") && style != "points"
                                  ? std::string("notitle")
                                  : "title " + quote_gp(str(series["name"]));
    std::string p;
    if (style == "points") {
      const int pt = series.value("symbol", std::string()) == "x" ? 2 : 7;
      const double ps = 0.1 * series.value("size", 7.0);
      p = fmt::format("{} using 1:2:3:4 with yerrorbars pt {} ps {:g} lw 1.2 lc rgb '{}' {}",
                      block, pt, ps, color, title);
      if (!bars) p = fmt::format("{} using 1:2 with points pt {} ps {:g} lc rgb '{}' {}", block,
                                 pt, ps, color, title);
    } else {
      const char* dash = style == "dashed" ? "dt 2" : style == "limit" ? "dt 3" : "dt 1";
      const double width = series.contains("width") ? series["width"].get<double>() * (2.2 / 2.4)
                           : style == "line" ? 2.2 : 1.6;
      p = fmt::format("{} using 1:2 with lines lw {} {} lc rgb '{}' {}", block, width, dash,
                      color, title);
    }
    plots += (plots.empty() ? "plot " : ", \\\n     ") + p;
    if (series.contains("label")) {
      const auto& l = series["label"];
      // Labels right of the middle are right-aligned so that they stay inside the frame.
      const bool right = figure.contains("x_range") &&
                         num(l["x"]) > std::sqrt(num(figure["x_range"][0]) * num(figure["x_range"][1]));
      s += fmt::format("set label {} at {:.10g},{:.10g} {} noenhanced tc rgb '{}' "
                       "font ',12' front\n",
                       quote_gp(str(l["text"])), num(l["x"]), num(l["y"]),
                       right ? "right offset -0.6,0.8" : "offset 0.6,0.8", color);
    }
  }
  s += plots + "\n";
  s += "set terminal pngcairo size 1440,960 enhanced font 'DejaVu Sans,18' background rgb 'white'\n";
  s += "set output " + quote_gp(png_path) + "\nreplot\nunset output\n";
  return s;
}

// ---------------------------------------------------------------- HTML

namespace {

constexpr const char* kCss = R"CSS(
:root { --ink:#1d2330; --muted:#5b6475; --line:#e3e6ec; --card:#f7f8fa; --pass:#1a7f37; --fail:#c62828; --warn:#b26a00; }
* { box-sizing: border-box; }
body { margin:0; font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color:var(--ink); background:#fff; }
header { padding:28px 40px 18px; border-bottom:1px solid var(--line); background:linear-gradient(180deg,#f3f6fb,#fff); }
header h1 { margin:0 0 4px; font-size:26px; font-weight:650; letter-spacing:-0.01em; }
header .sub { color:var(--muted); }
main { padding:8px 40px 40px; max-width:1400px; }
.cards { display:flex; flex-wrap:wrap; gap:14px; margin:18px 0 8px; }
.card { background:var(--card); border:1px solid var(--line); border-radius:10px; padding:12px 18px; min-width:150px; }
.card .k { color:var(--muted); font-size:12px; text-transform:uppercase; letter-spacing:.06em; }
.card .v { font-size:22px; font-weight:600; }
h2 { font-size:19px; margin:30px 0 10px; padding-bottom:4px; border-bottom:1px solid var(--line); }
table { border-collapse:collapse; margin:8px 0 6px; font-variant-numeric: tabular-nums; }
th, td { padding:6px 12px; border-bottom:1px solid var(--line); text-align:left; vertical-align:top; }
th { font-size:12px; color:var(--muted); text-transform:uppercase; letter-spacing:.05em; font-weight:600; }
td.num { text-align:right; white-space:nowrap; }
.ci { color:var(--muted); font-size:12.5px; }
.ni { color:#9aa1ad; }
.pill { display:inline-block; padding:1px 9px; border-radius:10px; font-size:12.5px; font-weight:600; color:#fff; }
.pill.pass { background:var(--pass); } .pill.fail { background:var(--fail); } .pill.other { background:#8a93a3; }
.soft { color:var(--muted); font-size:12.5px; }
.figs { display:grid; grid-template-columns: repeat(auto-fit, minmax(620px, 1fr)); gap:18px; }
figure { margin:0; border:1px solid var(--line); border-radius:10px; padding:8px 10px 10px; background:#fff; }
figure .plot { width:100%; height:540px; }
figure.hero { grid-column: 1 / -1; }
figure.hero .plot { height:600px; }
.matrix td { text-align:center; }
.matrix td .val { font-weight:600; }
figure img { width:100%; }
figcaption { color:var(--muted); font-size:13px; padding:2px 6px; }
ul.notes li { margin:3px 0; color:var(--muted); }
.err { color:var(--fail); }
@media print { header { background:none; } .figs { display:block; } figure { break-inside:avoid; margin-bottom:12px; } main, header { padding-left:0; padding-right:0; } }
)CSS";

constexpr const char* kScript = R"JS(
(function () {
  const PALETTE = %PALETTE%;
  const errors = [];
  function note(msg) { errors.push(String(msg)); document.body.setAttribute('data-errors', String(errors.length)); }
  window.addEventListener('error', function (e) { note(e.message); });
  const origError = console.error;
  console.error = function () { note(Array.from(arguments).join(' ')); origError.apply(console, arguments); };
  document.body.setAttribute('data-errors', '0');
  const report = JSON.parse(document.getElementById('report-data').textContent);
  function colorOf(s) { return typeof s.color === 'string' ? s.color : PALETTE[s.color % PALETTE.length]; }
  // The heat maps' colour scale (viridis stops; gnuplot_script defines the same palette).
  const SCALE = %SCALE%;
  function scaleColor(f) {
    f = Math.min(1, Math.max(0, f));
    for (let i = 1; i < SCALE.length; ++i) {
      if (f <= SCALE[i][0]) {
        const a = SCALE[i - 1], b = SCALE[i], u = (f - a[0]) / (b[0] - a[0]);
        const pa = parseInt(a[1].slice(1), 16), pb = parseInt(b[1].slice(1), 16);
        const mix = function (shift) { return Math.round(((pa >> shift) & 255) * (1 - u) + ((pb >> shift) & 255) * u); };
        return 'rgb(' + mix(16) + ',' + mix(8) + ',' + mix(0) + ')';
      }
    }
    return SCALE[SCALE.length - 1][1];
  }
  function trace(s, unit, fig) {
    const c = colorOf(s);
    const xname = fig.x_hover || 'τ', xunit = fig.x_hover_unit === undefined ? ' s' : fig.x_hover_unit;
    const t = { x: s.x, y: s.y, name: s.name, type: 'scatter', legendgroup: s.group || s.name,
                showlegend: !s.group || s.style === 'points',
                hovertemplate: (s.text ? '%{text}<br>' : '') + xname + ' = %{x:.4g}' + xunit + '<br>%{y:.4g} ' + unit + '<extra>' + s.name + '</extra>' };
    if (s.text) t.text = s.text;
    if (s.style === 'heatmap') {
      // Cells are layout shapes (heatmap(): the basic Plotly bundle has no heatmap trace);
      // this trace gives each cell's hover and the colour bar.
      const logs = s.z.map(function (z) { return Math.log10(z); });
      t.mode = 'markers';
      t.marker = { color: logs, colorscale: SCALE, cmin: s.z_log_range[0], cmax: s.z_log_range[1], size: 5, opacity: 0.01,
                   colorbar: { title: { text: 'log10 ' + s.z_label, side: 'right' }, thickness: 14 } };
      t.hovertemplate = xname + ' = %{x:.4g}' + xunit + '<br>τ = %{y:.4g} s<br>' + s.z_label + ' = %{text}<extra></extra>';
      t.text = s.z.map(function (z) { return z.toPrecision(4); });
      t.showlegend = false;
    } else if (s.style === 'points') {
      t.mode = 'markers';
      t.marker = { color: c, size: s.size || 7, symbol: s.symbol || 'circle' };
      if (s.y_low) {
        t.error_y = { type: 'data', symmetric: false, color: c, thickness: 1.3, width: 3,
                      array: s.y_high.map(function (h, i) { return h == null ? 0 : h - s.y[i]; }),
                      arrayminus: s.y_low.map(function (l, i) { return l == null ? 0 : s.y[i] - l; }) };
      }
    } else {
      t.mode = 'lines';
      t.line = { color: c, width: s.width || (s.style === 'line' ? 2.4 : 1.6),
                 dash: s.style === 'dashed' ? 'dash' : s.style === 'limit' ? 'dot' : 'solid' };
    }
    return t;
  }
  function heatmap(s, fig) {
    // Shape corners are data values on every axis type (Plotly 2: unlike annotations, no log10
    // on log axes).
    const shapes = [];
    const lx = function (v) { return v; };
    const ly = function (v) { return v; };
    const span = s.z_log_range[1] - s.z_log_range[0] || 1;
    s.z.forEach(function (z, i) {
      shapes.push({ type: 'rect', layer: 'below', line: { width: 0 }, xref: 'x', yref: 'y',
                    x0: lx(s.x_low[i]), x1: lx(s.x_high[i]), y0: ly(s.y_low[i]), y1: ly(s.y_high[i]),
                    fillcolor: scaleColor((Math.log10(z) - s.z_log_range[0]) / span) });
    });
    return shapes;
  }
  function axis(label, log, range) {
    const r = range ? (log ? range.map(Math.log10) : range) : undefined;
    // Decade ticks unless the range is narrower than two decades (a fleet's spread).
    const decades = log && !(r && r[1] - r[0] < 2);
    return { range: r, autorange: r ? false : true, title: { text: label }, type: log ? 'log' : 'linear', exponentformat: 'power', dtick: decades ? 1 : undefined,
             showgrid: true, gridcolor: '#e8eaee', zeroline: false, linecolor: '#888', mirror: true, ticks: 'outside' };
  }
  let drawn = 0;
  report.figures.forEach(function (fig, i) {
    const div = document.getElementById('fig-' + i);
    if (!div) { note('no element for figure ' + fig.id); return; }
    const hero = i === 0 && fig.id.indexOf('adev_all') === 0;
    const unit = (fig.y_label.match(/\[(.*)\]$/) || ['', ''])[1];
    const annotations = [];
    fig.series.forEach(function (s) {
      if (!s.label) return;
      // Labels right of the middle point left, so that they stay inside the frame.
      const right = fig.x_range && s.label.x > Math.sqrt(fig.x_range[0] * fig.x_range[1]);
      annotations.push({ x: fig.x_log ? Math.log10(s.label.x) : s.label.x,
                         y: fig.y_log ? Math.log10(s.label.y) : s.label.y,
                         text: s.label.text, showarrow: true, arrowhead: 0, ax: right ? -34 : 28, ay: -26,
                         font: { size: 12, color: PALETTE[s.color % PALETTE.length] },
                         bgcolor: 'rgba(255,255,255,0.85)' });
    });
    const layout = { title: { text: fig.title, font: { size: 16 }, x: 0.01, xanchor: 'left' }, xaxis: axis(fig.x_label, fig.x_log, fig.x_range),
                     yaxis: axis(fig.y_label, fig.y_log, fig.y_range), annotations: annotations,
                     margin: { l: 70, r: 20, t: 50, b: hero ? 55 : 120 }, hovermode: 'closest',
                     legend: hero ? { x: 0.01, y: 0.01, xanchor: 'left', yanchor: 'bottom', bgcolor: 'rgba(255,255,255,0.85)', bordercolor: '#ddd', borderwidth: 1, font: { size: 11 } }
                                 : { orientation: 'h', x: 0, y: -0.2, yanchor: 'top', font: { size: 11 } },
                     font: { family: 'system-ui, -apple-system, Segoe UI, Roboto, DejaVu Sans, sans-serif' } };
    const traces = fig.series.map(function (s) { return trace(s, unit, fig); });
    fig.series.forEach(function (s) { if (s.style === 'heatmap') layout.shapes = (layout.shapes || []).concat(heatmap(s, fig)); });
    try {
      Plotly.newPlot(div, traces, layout, { responsive: true, displaylogo: false, displayModeBar: 'hover' }).then(function () {
        div.setAttribute('data-rendered-points', String(div.querySelectorAll('.scatterlayer .point').length));
        div.setAttribute('data-rendered-traces', String(div.querySelectorAll('.scatterlayer .trace').length));
        // Heat-map cells drawn, and how many fall outside the axes' ranges (misplaced).
        const shapes = (div._fullLayout && div._fullLayout.shapes) || [];
        const inside = function (ax, a, b) {
          const r = ax.type === 'log' ? ax.range.map(function (v) { return Math.pow(10, v); }) : ax.range;
          const lo = Math.min(r[0], r[1]), hi = Math.max(r[0], r[1]), eps = 1e-9 * (hi - lo);
          return a >= lo - eps && b <= hi + eps && a < b;
        };
        let outside = 0;
        shapes.forEach(function (sh) {
          if (!inside(div._fullLayout.xaxis, Math.min(sh.x0, sh.x1), Math.max(sh.x0, sh.x1)) ||
              !inside(div._fullLayout.yaxis, Math.min(sh.y0, sh.y1), Math.max(sh.y0, sh.y1))) outside += 1;
        });
        div.setAttribute('data-rendered-shapes', String(div.querySelectorAll('.shapelayer path').length));
        div.setAttribute('data-shapes-outside', String(outside));
        drawn += 1;
        document.body.setAttribute('data-figures-drawn', String(drawn));
      }).catch(note);
    } catch (e) { note(e); }
  });
})();
)JS";

std::string pill(const std::string& verdict) {
  const std::string cls = verdict == "pass" ? "pass" : verdict == "fail" ? "fail" : "other";
  std::string text = verdict;
  for (auto& c : text) if (c == '_') c = ' ';
  return "<span class=\"pill " + cls + "\">" + html_escape(text) + "</span>";
}

std::string embed_json(const json& doc) {
  std::string text = doc.dump(-1, ' ', true);  // ASCII only: safe in any page encoding
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

}  // namespace

std::string html_escape_text(const std::string& s) { return html_escape(s); }

std::string html_page_head(const std::string& title, const std::string& plotly_js) {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  h += "<title>" + html_escape(title) + "</title>\n<style>" + kCss + "</style>\n";
  if (!plotly_js.empty()) h += "<script>" + plotly_js + "</script>\n";
  h += "</head>\n<body>\n<header><h1>" + html_escape(title) + "</h1>";
  return h;
}

std::string html_figures(const json& figures, bool interactive) {
  std::string h = "<div class=\"figs\" style=\"margin-top:18px\">\n";
  int i = 0;
  for (const auto& f : figures) {
    const std::string stem = file_stem(str(f["id"]));
    const bool hero = (i == 0 && str(f["id"]).rfind("adev_all", 0) == 0) || f.value("wide", false);
    h += "<figure id=\"figure-" + html_escape(stem) + "\"" + (hero ? " class=\"hero\"" : "") + ">";
    if (interactive) {
      h += fmt::format("<div class=\"plot\" id=\"fig-{}\"></div>", i);
    } else {
      h += "<img src=\"figures/" + stem + ".svg\" alt=\"" + html_escape(str(f["title"])) + "\">";
    }
    h += "<figcaption>" + html_escape(str(f["caption"])) + " <a href=\"figures/" + stem +
         ".svg\">SVG</a> · <a href=\"figures/" + stem + ".png\">PNG</a></figcaption></figure>\n";
    ++i;
  }
  h += "</div>\n";
  return h;
}

std::string html_page_tail(const json& doc, bool interactive) {
  std::string h = "</main>\n";
  if (interactive) {
    h += "<script type=\"application/json\" id=\"report-data\">" + embed_json(doc) + "</script>\n";
    std::string palette = "[";
    for (int c = 0; c < 8; ++c) palette += std::string(c ? "," : "") + "'" + palette_color(c) + "'";
    palette += "]";
    std::string script = kScript;
    script.replace(script.find("%PALETTE%"), 9, palette);
    script.replace(script.find("%SCALE%"), 7, heat_scale_js());
    h += "<script>" + script + "</script>\n";
  }
  h += "</body>\n</html>\n";
  return h;
}

std::string markdown_figures(const json& figures) {
  std::string md = "\n## Figures\n\n";
  for (const auto& f : figures) {
    const std::string stem = file_stem(str(f["id"]));
    md += fmt::format("### {}\n\n![{}](figures/{}.svg)\n\n{} ([PNG](figures/{}.png))\n\n",
                      str(f["title"]), str(f["title"]), stem, str(f["caption"]), stem);
  }
  return md;
}

std::string render_html(const json& doc, const std::string& plotly_js) {
  const bool interactive = !plotly_js.empty();
  std::string h = html_page_head(str(doc["title"]), plotly_js);
  const auto& channels = doc["channels"];
  double rate = 0, duration = 0;
  std::size_t ok = 0;
  for (const auto& ch : channels) {
    rate = num(ch["rate_hz"]);
    duration = std::max(duration, num(ch["duration_s"]));
    if (!ch.contains("error")) ++ok;
  }
  h += fmt::format("<div class=\"sub\">imunoise {} · overlapping Allan deviation, noise model "
                   "(paper eq. 5, method {}), {} intervals</div></header>\n<main>\n",
                   html_escape(str(doc["version"])), html_escape(str(doc["options"]["fit_method"])),
                   level_text(doc));
  // Summary cards.
  h += "<div class=\"cards\">";
  h += fmt::format("<div class=\"card\"><div class=\"k\">channels</div><div class=\"v\">{} / {}</div></div>",
                   ok, channels.size());
  h += fmt::format("<div class=\"card\"><div class=\"k\">sample rate</div><div class=\"v\">{:g} Hz</div></div>", rate);
  h += fmt::format("<div class=\"card\"><div class=\"k\">record</div><div class=\"v\">{}</div></div>",
                   duration_text(duration));
  if (!doc["options"]["spec"].is_null()) {
    std::size_t pass = 0, judged = 0;
    for (const auto& ch : channels) {
      if (ch["spec_comparison"].is_null()) continue;
      ++judged;
      if (ch["spec_comparison"]["all_pass"].get<bool>()) ++pass;
    }
    h += fmt::format("<div class=\"card\"><div class=\"k\">datasheet {}</div><div class=\"v\">{} / {} pass</div></div>",
                     html_escape(str(doc["options"]["spec"])), pass, judged);
  }
  h += "</div>\n";
  // Figures.
  h += html_figures(doc["figures"], interactive);
  // Noise-model table.
  const auto terms = shown_terms(doc);
  h += fmt::format("<h2>Noise model</h2>\n<p class=\"soft\">Coefficients of the paper's eq. 5 "
                   "fitted to the overlapping Allan variance; {} confidence intervals below each "
                   "value. A term the record cannot support is shown as an upper limit.</p>\n",
                   level_text(doc));
  h += "<table><tr><th>channel</th>";
  for (const auto& t : terms) h += "<th>" + t + "</th>";
  h += "<th>χ²/dof</th></tr>\n";
  for (const auto& ch : channels) {
    h += "<tr><td>" + html_escape(str(ch["name"])) + "</td>";
    if (ch["fit"].is_null()) {
      h += fmt::format("<td colspan=\"{}\" class=\"err\">{}</td></tr>\n", terms.size() + 1,
                       html_escape(ch.contains("error") ? str(ch["error"]) : "no fit"));
      continue;
    }
    for (const auto& t : terms) {
      if (outside_gmwm_model(ch, t)) {
        h += "<td class=\"num ni\">–<br><span class=\"ci\">not in the model</span></td>";
        continue;
      }
      const auto tt = term_text(ch["fit"]["terms"][t]);
      if (tt.identified) {
        h += fmt::format("<td class=\"num\">{} <span class=\"soft\">{}</span><br><span class=\"ci\">{}</span></td>",
                         tt.value, html_escape(tt.unit), tt.ci);
      } else {
        h += fmt::format("<td class=\"num ni\">{} <span class=\"soft\">{}</span><br><span class=\"ci\">not identified</span></td>",
                         html_escape(tt.value), html_escape(tt.unit));
      }
    }
    h += "<td class=\"num\">" + g(ch["fit"]["diagnostics"]["chi2_dof"], 3) + "</td></tr>\n";
  }
  h += "</table>\n";
  if (const auto extras = extra_term_rows(doc); !extras.empty()) {
    h += "<p class=\"soft\">Correlated and periodic terms: each first-order Gauss-Markov term (sigma, "
         "correlation time T_c; GM1, GM2, ... by correlation time) and the sinusoid (amplitude, "
         "frequency f).</p>\n<table><tr><th>channel</th><th>term</th><th>magnitude</th><th>T_c or f</th></tr>\n";
    const auto cell = [](const TermText& t, const std::string& prefix) {
      return t.identified
                 ? fmt::format("<td class=\"num\">{}{} <span class=\"soft\">{}</span><br><span class=\"ci\">{}</span></td>",
                               prefix, html_escape(t.value), html_escape(t.unit), t.ci)
                 : fmt::format("<td class=\"num ni\">{}{} <span class=\"soft\">{}</span><br><span class=\"ci\">not "
                               "identified</span></td>",
                               prefix, html_escape(t.value), html_escape(t.unit));
    };
    for (const auto& r : extras) {
      h += "<tr><td>" + html_escape(r.channel) + "</td><td>" + r.term + "</td>" + cell(r.magnitude, "") +
           cell(r.shape, r.shape_name + " = ") + "</tr>\n";
    }
    h += "</table>\n";
  }
  if (const auto selection = selection_rows(doc); !selection.empty()) {
    h += "<h2>Model selection (gmwm)</h2>\n<p class=\"soft\">The model of least WVIC (wavelet variance "
         "information criterion) among the candidates; J: the moment conditions' goodness of fit (χ² on "
         "its dof for an exact model). Every candidate is in report.json (fit.gmwm.candidates).</p>\n"
         "<table><tr><th>channel</th><th>model</th><th>J</th><th>WVIC</th><th>next best</th><th>candidates</th></tr>\n";
    for (const auto& r : selection) {
      h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td><td "
                       "class=\"num\">{}</td></tr>\n",
                       html_escape(r.channel), html_escape(r.model), html_escape(r.j), r.wvic,
                       html_escape(r.runner_up), r.candidates);
    }
    h += "</table>\n";
  }
  // Datasheet comparison: one row per channel, one column per datasheet term.
  bool any_spec = false;
  for (const auto& ch : channels) any_spec = any_spec || !ch["spec_comparison"].is_null();
  if (any_spec) {
    std::vector<std::pair<std::string, std::string>> spec_terms;  // symbol, heading
    for (const auto& ch : channels) {
      if (ch["spec_comparison"].is_null()) continue;
      for (const auto& t : ch["spec_comparison"]["terms"]) {
        if (!t.contains("spec")) continue;
        const std::string sym = str(t["symbol"]);
        bool known = false;
        for (const auto& st : spec_terms) known = known || st.first == sym;
        if (!known) {
          spec_terms.emplace_back(sym, sym + " " + str(t["title"]) + " ≤ " + g(t["spec"]["limit"]) +
                                           " " + str(t["spec"]["unit"]));
        }
      }
      break;
    }
    h += "<h2>Datasheet comparison: " + html_escape(str(doc["options"]["spec"])) + "</h2>\n";
    h += "<p class=\"soft\">Pass if measured ≤ spec × (1 + tolerance); conclusive when the whole "
         "confidence interval lies on the verdict's side of the limit. Terms the datasheet does "
         "not give are in the noise-model table.</p>\n";
    h += "<table class=\"matrix\"><tr><th>channel</th>";
    for (const auto& st : spec_terms) h += "<th>" + html_escape(st.second) + "</th>";
    h += "</tr>\n";
    for (const auto& ch : channels) {
      const auto& c = ch["spec_comparison"];
      if (c.is_null()) continue;
      h += "<tr><td style=\"text-align:left\">" + html_escape(str(ch["name"])) + "</td>";
      for (const auto& st : spec_terms) {
        std::string cell = "<td>–</td>";
        for (const auto& t : c["terms"]) {
          if (str(t["symbol"]) != st.first || !t.contains("spec")) continue;
          const json& m = t["measured_in_spec_unit"];
          const std::string verdict = str(t["verdict"]);
          const bool judged = verdict == "pass" || verdict == "fail";
          cell = fmt::format(
              "<td><span class=\"val\">{} {}</span> <span class=\"soft\">{}</span><br>{} "
              "<span class=\"soft\">{}</span><br><span class=\"ci\">[{}, {}]</span></td>",
              g(m["value"]), html_escape(str(m["unit"])),
              t["deviation_percent"].is_number() ? fmt::format("{:+.1f} %", num(t["deviation_percent"]))
                                                 : std::string(),
              pill(verdict), judged ? (t["conclusive"].get<bool>() ? "conclusive" : "inconclusive") : "",
              g(m["ci_low"], 3), g(m["ci_high"], 3));
        }
        h += cell;
      }
      h += "</tr>\n";
    }
    h += "</table>\n";
  }
  const auto navs = nav_rows(doc);
  if (!navs.empty()) {
    h += fmt::format("<h2>Navigation error after {:g} h</h2>\n<p class=\"soft\">RMS errors of a "
                     "free-inertial system whose gyros all have the channel's fitted noise "
                     "(latitude {:g} deg). The paper published 0.37 deg, 22.6 km and 3.9 deg "
                     "from its eq. 6.</p>\n<table><tr><th>channel</th><th>model</th>"
                     "<th>latitude</th><th>path</th><th>longitude</th></tr>\n",
                     navs.front().t_s / 3600.0, num(doc["options"]["nav_latitude_deg"]));
    for (const auto& r : navs) {
      h += fmt::format("<tr><td>{}</td><td>{}</td><td class=\"num\">{} deg</td><td class=\"num\">{} km</td>"
                       "<td class=\"num\">{} deg</td></tr>\n",
                       html_escape(r.channel), r.model, fixed(r.lat_deg, 3),
                       fixed(r.path_m / 1000.0, 3), fixed(r.lon_deg, 3));
    }
    h += "</table>\n";
  }
  if (const auto davars = davar_lines(doc); !davars.empty()) {
    h += "<h2>Stationarity (dynamic Allan variance)</h2>\n<ul>";
    for (const auto& [name, text] : davars) h += "<li>" + html_escape(text) + "</li>";
    h += "</ul>\n<p class=\"soft\">A window is flagged when its Allan variance at a tau lies outside "
         "the chi-squared band around the median of all windows (Bonferroni over windows and taus: "
         "a stationary record is called non-stationary with probability &lt; 0.001). The heat map "
         "shows every window.</p>\n";
  }
  if (!doc["redundant"].is_null()) {
    const auto& r = doc["redundant"];
    h += "<h2>Redundant unit: " + html_escape(str(r["geometry"])) + "</h2>\n";
    h += "<div class=\"cards\">";
    h += fmt::format("<div class=\"card\"><div class=\"k\">sensors</div><div class=\"v\">{}</div></div>",
                     r["n_sensors"].get<int>());
    std::string gains;
    for (const auto& v : r["axis_gain"]) gains += (gains.empty() ? "" : " / ") + g(v, 3);
    h += "<div class=\"card\"><div class=\"k\">fused axis gain x / y / z</div><div class=\"v\">" +
         gains + "</div></div>";
    h += "<div class=\"card\"><div class=\"k\">GDOP</div><div class=\"v\">" + g(r["gdop"], 4) +
         "</div></div>";
    h += fmt::format("<div class=\"card\"><div class=\"k\">single fault</div><div class=\"v\">{}</div></div>",
                     r["isolable"].get<bool>() ? "isolable" : r["detectable"].get<bool>() ? "detectable" : "undetectable");
    h += "</div>\n<p class=\"soft\">Axis gain: the fused axis' noise over one sensor's (identical "
         "sensors). The figure of the fused axes compares the measured fused curves with the noise "
         "predicted from the sensors' fits. Every number of the analysis (fusion matrix, parity, "
         "detection thresholds, minimum detectable faults) is in report.json under \"redundant\".</p>\n";
    h += "<p>" + html_escape(fault_summary(r)) + "</p>\n";
  }
  if (doc.contains("reference") && !doc["reference"].is_null()) {
    h += "<h2>" + html_escape(str(doc["reference"]["title"])) + "</h2>\n" +
         str(doc["reference"]["html"]) + "\n";
  }
  // Notes.
  std::string notes;
  for (const auto& n : doc["notes"]) notes += "<li>" + html_escape(str(n)) + "</li>";
  for (const auto& in : doc["inputs"]) {
    if (in["status"] != "ok") {
      notes += "<li class=\"err\">" + html_escape(str(in["source"])) + ": " +
               html_escape(str(in["error"])) + "</li>";
    }
  }
  for (const auto& ch : channels) {
    for (const auto& w : ch["warnings"]) {
      notes += "<li>" + html_escape(str(ch["name"])) + ": " + html_escape(str(w)) + "</li>";
    }
  }
  if (doc["kalibr"]["written"].get<bool>()) {
    notes += "<li>imu.yaml (Kalibr): " + html_escape(str(doc["kalibr"]["rule"])) + "</li>";
  }
  notes += "<li>Tables: curves.csv, coefficients.csv" +
           std::string(any_spec ? ", spec_comparison.csv" : "") +
           "; every number of this page is in report.json.</li>";
  h += "<h2>Notes</h2>\n<ul class=\"notes\">" + notes + "</ul>\n";
  h += html_page_tail(doc, interactive);
  return h;
}

}  // namespace imunoise::study
