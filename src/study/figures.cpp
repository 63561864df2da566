#include "imunoise/study/figures.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/core.h>

namespace imunoise::study {
namespace {

// Colour-blind-safe (Okabe-Ito), darkest first so that four gyros stay distinct in print.
constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#000000", "#F0E442"};

nlohmann::json curve_series(const nlohmann::json& curve, const std::string& name, int color) {
  nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array();
  nlohmann::json lo = nlohmann::json::array(), hi = nlohmann::json::array();
  bool bounds = false;
  for (const auto& p : curve["points"]) {
    if (p["dev"].is_null() || p["dev"].get<double>() <= 0.0) continue;
    x.push_back(p["tau_s"]);
    y.push_back(p["dev"]);
    lo.push_back(p["ci_low"]);
    hi.push_back(p["ci_high"]);
    bounds = bounds || !p["ci_low"].is_null();
  }
  nlohmann::json s{{"name", name}, {"style", "points"}, {"color", color}, {"x", x}, {"y", y}};
  if (bounds) {
    s["y_low"] = lo;
    s["y_high"] = hi;
  }
  return s;
}

const nlohmann::json* find_curve(const nlohmann::json& channel, const std::string& label) {
  for (const auto& c : channel["curves"]) {
    if (c["estimator"] == label) return &c;
  }
  return nullptr;
}

std::string fmt_g(double v) { return fmt::format("{:.4g}", v); }

std::string ci_text(const nlohmann::json& doc) {
  return std::to_string(static_cast<int>(100.0 * doc["options"]["curve_ci_level"].get<double>() + 0.5)) +
         " %";
}

// Axis ranges from the measured points (with their bars) so that asymptotes and datasheet
// lines running far outside do not squash the data; lines are clipped at the frame.
void set_ranges(nlohmann::json& figure) {
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  bool have_points = false;
  for (const auto& s : figure["series"]) have_points = have_points || s["style"] == "points";
  for (const auto& s : figure["series"]) {
    for (const auto& x : s["x"]) {
      if (x.is_number() && x.get<double>() > 0) {
        x_lo = std::min(x_lo, x.get<double>());
        x_hi = std::max(x_hi, x.get<double>());
      }
    }
    if (have_points && s["style"] != "points") continue;
    for (const char* key : {"y", "y_low", "y_high"}) {
      if (!s.contains(key)) continue;
      for (const auto& y : s[key]) {
        if (y.is_number() && y.get<double>() > 0) {
          y_lo = std::min(y_lo, y.get<double>());
          y_hi = std::max(y_hi, y.get<double>());
        }
      }
    }
  }
  if (!(x_hi > x_lo) || !(y_hi > y_lo)) return;
  figure["x_range"] = {x_lo / 1.5, x_hi * 1.5};
  figure["y_range"] = {y_lo / 2.0, y_hi * 1.6};
}


// Navigation error growth of the first gyro with a navigation result, one figure per
// quantity (the paper's Figures 5-7), one line per model, the paper's published 1-hour value
// as a point.
void nav_figures(const nlohmann::json& doc, nlohmann::json& figures) {
  const nlohmann::json* nav = nullptr;
  std::string name;
  for (const auto& ch : doc["channels"]) {
    if (ch.contains("nav") && !ch["nav"].is_null()) {
      nav = &ch["nav"];
      name = ch["name"].get<std::string>();
      break;
    }
  }
  if (nav == nullptr) return;
  struct Quantity { const char* id; const char* key; const char* title; const char* y_label; double scale; const char* published; };
  const Quantity quantities[] = {
      {"nav_latitude", "lat_deg", "Latitude error", "latitude error [deg]", 1.0, "lat_deg"},
      {"nav_path", "path_m", "Position error along the path", "path error [km]", 1e-3, "path_m"},
      {"nav_longitude", "lon_deg", "Longitude error", "longitude error [deg]", 1.0, "lon_deg"}};
  for (const auto& q : quantities) {
    nlohmann::json series = nlohmann::json::array();
    int color = 0;
    for (const auto& m : (*nav)["models"]) {
      if (!m.contains(q.key) || m[q.key].is_null()) continue;
      nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array();
      for (std::size_t i = 0; i < m["t_s"].size(); ++i) {
        if (!m[q.key][i].is_number()) continue;
        x.push_back(m["t_s"][i].get<double>() / 60.0);
        y.push_back(m[q.key][i].get<double>() * q.scale);
      }
      // Models that agree would hide each other: the later ones are dashed.
      series.push_back({{"name", m["model"]}, {"style", color == 0 ? "line" : "dashed"}, {"color", color++},
                        {"x", std::move(x)}, {"y", std::move(y)}});
      if (m.contains("published") && m["published"].is_object() &&
          m["published"].contains(q.published) && m["published"][q.published].is_number()) {
        const double t = m["published"].value("t_s", 3600.0) / 60.0;
        series.push_back({{"name", "paper, published"}, {"style", "points"}, {"color", 6},
                          {"x", {t}}, {"y", {m["published"][q.published].get<double>() * q.scale}}});
      }
    }
    if (series.empty()) continue;
    figures.push_back({{"id", q.id},
                       {"title", std::string(q.title) + " from the noise of " + name},
                       {"caption", "RMS error of a free-inertial system whose gyros all have the "
                                   "noise model fitted to " + name + ", per navigation model "
                                   "(schuler: Schuler-loop closed forms; covariance: the linearised "
                                   "error model with Earth rate; montecarlo: the same model driven "
                                   "by simulated noise, 1000 runs; paper, when asked: the published "
                                   "eq. 6, its 1-hour value the black point)."},
                       {"x_label", "time [min]"},
                       {"y_label", q.y_label},
                       {"x_log", false},
                       {"y_log", false},
                       {"series", std::move(series)}});
  }
}

// The error budget of the covariance model (the whole IMU's when the study has one, else the
// first gyro's): each term's share of the horizontal position variance versus time, stacked
// (each line the sum of the terms below it, largest first), so the gap between two lines is a
// term's share; the caption names the term to improve first.
void budget_figure(const nlohmann::json& doc, nlohmann::json& figures) {
  const nlohmann::json* nav = nullptr;
  std::string name;
  if (doc.contains("imu_nav") && !doc["imu_nav"].is_null()) {
    nav = &doc["imu_nav"]["nav"];
    name = "the whole IMU";
  } else {
    for (const auto& ch : doc["channels"]) {
      if (ch.contains("nav") && !ch["nav"].is_null()) {
        nav = &ch["nav"];
        name = ch["name"].get<std::string>() + " on every axis";
        break;
      }
    }
  }
  if (nav == nullptr) return;
  const nlohmann::json* model = nullptr;
  for (const auto& m : (*nav)["models"]) {
    if (m.contains("budget") && !m["budget"].empty()) model = &m;
  }
  if (model == nullptr) return;
  const auto& t = (*model)["t_s"];
  std::vector<std::pair<double, std::string>> order;
  for (const auto& [term, shares] : (*model)["budget"].items()) order.emplace_back(shares.back().get<double>(), term);
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> sum(t.size(), 0.0);
  nlohmann::json series = nlohmann::json::array();
  int color = 0;
  for (const auto& [last, term] : order) {
    const auto& shares = (*model)["budget"][term];
    nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array();
    for (std::size_t i = 1; i < t.size(); ++i) {
      sum[i] += shares[i].get<double>();
      x.push_back(t[i].get<double>() / 60.0);
      y.push_back(100.0 * sum[i]);
    }
    series.push_back({{"name", (color == 0 ? "" : "+ ") + term}, {"style", "line"}, {"color", color++},
                      {"x", std::move(x)}, {"y", std::move(y)}});
  }
  figures.push_back({{"id", "nav_budget"},
                     {"title", "Error budget of " + name + ": each term's share of the position error"},
                     {"caption", "Share of the horizontal position variance per noise term (covariance model), "
                                 "stacked: each line adds its term to those below it. At the end of the run " +
                                     order.front().second + " is the largest share (" +
                                     fmt::format("{:.0f}", 100.0 * order.front().first) + " %): improve it first."},
                     {"x_label", "time [min]"},
                     {"y_label", "cumulative share [%]"},
                     {"x_log", false},
                     {"y_log", false},
                     {"series", std::move(series)}});
}

// Allan variance of eq. 5 from a {Q, N, B, K, R} block of values in one unit.
double model_adev(const nlohmann::json& terms, double tau) {
  auto v = [&](const char* k) {
    return terms.contains(k) && terms[k].contains("value") && terms[k]["value"].is_number()
               ? terms[k]["value"].get<double>() : 0.0;
  };
  const double q = v("Q"), n = v("N"), b = v("B"), k = v("K"), r = v("R");
  return std::sqrt(3 * q * q / (tau * tau) + n * n / tau + 2 * std::log(2.0) / M_PI * b * b +
                   k * k * tau / 3 + r * r * tau * tau / 2);
}

// The fused body axes of a redundant unit: measured curves of the fused samples, the model the
// redundant analysis predicts from the sensors' fits, and one sensor for comparison.
void fused_figure(const nlohmann::json& doc, nlohmann::json& figures) {
  const auto& red = doc["redundant"];
  if (red.is_null() || !red.contains("fused_curves")) return;
  nlohmann::json series = nlohmann::json::array();
  int color = 0;
  std::string unit;
  for (const auto& c : red["fused_curves"]) {
    unit = c["unit"].get<std::string>();
    series.push_back(curve_series(c, c["estimator"].get<std::string>(), color));
    series.back()["group"] = c["estimator"];
    if (red.contains("axes") && static_cast<std::size_t>(color) < red["axes"].size()) {
      nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array();
      for (const auto& p : c["points"]) {
        x.push_back(p["tau_s"]);
        y.push_back(model_adev(red["axes"][static_cast<std::size_t>(color)], p["tau_s"].get<double>()));
      }
      series.push_back({{"name", c["estimator"].get<std::string>() + " predicted"},
                        {"group", c["estimator"]}, {"style", "line"}, {"color", color},
                        {"x", std::move(x)}, {"y", std::move(y)}});
    }
    ++color;
  }
  const auto& first = doc["channels"][0];
  if (first.contains("model") && !first["model"].is_null()) {
    series.push_back({{"name", "one sensor (" + first["name"].get<std::string>() + ") model"},
                      {"style", "dashed"}, {"color", 6},
                      {"x", first["model"]["tau_s"]}, {"y", first["model"]["adev"]}});
  }
  figures.push_back(
      {{"id", "adev_fused"},
       {"title", "Fused body axes of the redundant unit (" + red["geometry"].get<std::string>() + ")"},
       {"caption", "Points: overlapping Allan deviation of the fused axes x, y, z (the weighted "
                   "least-squares fusion applied to the samples) with " + ci_text(doc) +
                   " confidence bars; solid: the fused noise predicted from the sensors' fits; "
                   "dashed: one sensor's fitted model."},
       {"x_label", "averaging time tau [s]"},
       {"y_label", "Allan deviation [" + unit + "]"},
       {"x_log", true},
       {"y_log", true},
       {"series", std::move(series)}});
}
// The dynamic Allan deviation of a channel as a heat map: time (window centre) x tau, colour
// the window's Allan deviation; cells outside the stationarity band crossed; the times where
// the flagged state changes as dashed lines.
void davar_figure(const nlohmann::json& ch, nlohmann::json& figures) {
  if (!ch.contains("davar") || ch["davar"].is_null()) return;
  const auto& d = ch["davar"];
  const std::string name = ch["name"].get<std::string>();
  const double step = d["step_s"].get<double>(), window = d["window_s"].get<double>();
  nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array(), z = nlohmann::json::array();
  nlohmann::json xl = nlohmann::json::array(), xh = nlohmann::json::array();
  nlohmann::json yl = nlohmann::json::array(), yh = nlohmann::json::array();
  nlohmann::json fx = nlohmann::json::array(), fy = nlohmann::json::array();
  double z_lo = INFINITY, z_hi = 0.0, t_hi = 0.0;
  const auto& taus = d["tau_s"];
  for (std::size_t w = 0; w < d["adev"].size(); ++w) {
    const double centre = d["window_start_s"][w].get<double>() + window / 2.0;
    t_hi = std::max(t_hi, centre + step / 2.0);
    for (std::size_t j = 0; j < taus.size(); ++j) {
      const auto& v = d["adev"][w][j];
      if (!v.is_number()) continue;
      const double tau = taus[j].get<double>();
      x.push_back(centre);
      y.push_back(tau);
      z.push_back(v);
      xl.push_back(centre - step / 2.0);
      xh.push_back(centre + step / 2.0);
      yl.push_back(tau / std::sqrt(2.0));
      yh.push_back(tau * std::sqrt(2.0));
      z_lo = std::min(z_lo, v.get<double>());
      z_hi = std::max(z_hi, v.get<double>());
      if (d["flagged"][w][j].get<bool>()) {
        fx.push_back(centre);
        fy.push_back(tau);
      }
    }
  }
  if (z.empty()) return;
  const std::string unit = d["unit"].get<std::string>();
  nlohmann::json series = nlohmann::json::array();
  series.push_back({{"name", "Allan deviation per window"}, {"style", "heatmap"}, {"color", 0},
                    {"x", x}, {"y", y}, {"z", z}, {"x_low", xl}, {"x_high", xh}, {"y_low", yl},
                    {"y_high", yh}, {"z_label", "Allan deviation [" + unit + "]"},
                    {"z_log_range", {std::log10(z_lo), std::log10(z_hi)}}});
  const double tau_lo = taus.front().get<double>() / std::sqrt(2.0);
  const double tau_hi = taus.back().get<double>() * std::sqrt(2.0);
  if (!fx.empty()) {
    series.push_back({{"name", "outside the stationarity band"}, {"style", "points"}, {"symbol", "x"},
                      {"size", 8}, {"color", "#ff2a2a"}, {"x", fx}, {"y", fy}});
  }
  // One legend entry for all the change times (the later lines share the first's group).
  std::string changes;
  for (const auto& t : d["change_times_s"]) changes += (changes.empty() ? "" : ", ") + fmt_g(t.get<double>());
  const std::string changes_name = "changes near t = " + changes + " s";
  int k = 0;
  for (const auto& t : d["change_times_s"]) {
    series.push_back({{"name", changes_name}, {"style", "dashed"}, {"color", "#ff2a2a"}, {"width", 2.0},
                      {"x", {t, t}}, {"y", {tau_lo, tau_hi}}});
    if (k++ > 0) series.back()["group"] = changes_name;
  }
  const bool stationary = d["stationary"].get<bool>();
  std::string verdict = stationary ? "stationary" : "not stationary";
  figures.push_back(
      {{"id", "davar_" + name},
       {"title", "Dynamic Allan deviation of " + name + ": " + verdict},
       {"caption", "Overlapping Allan deviation in windows of " + fmt_g(window) + " s every " +
                       fmt_g(step) + " s (colour, log scale) against the window's centre and tau. "
                       "Crosses: windows whose Allan variance lies outside the chi-squared band "
                       "around the median of all windows (" + d["n_flagged_windows"].dump() + " of " +
                       d["n_windows"].dump() + " windows flagged); dashed: where the flagged state "
                       "changes. Verdict: " + verdict + "."},
       {"x_label", "time, window centre [s]"},
       {"y_label", "averaging time tau [s]"},
       {"x_log", false},
       {"y_log", true},
       {"x_hover", "t"},
       {"legend", "below"},
       {"x_range", {0.0, t_hi}},
       {"y_range", {tau_lo, tau_hi}},
       {"series", std::move(series)}});
}
}  // namespace

const char* palette_color(int index) {
  constexpr int n = sizeof(kPalette) / sizeof(kPalette[0]);
  return kPalette[((index % n) + n) % n];
}

nlohmann::json build_figures(const nlohmann::json& doc) {
  nlohmann::json figures = nlohmann::json::array();
  const auto& channels = doc["channels"];
  // 1. All channels of one quantity overlaid (the paper's Table 2 situation).
  for (const std::string quantity : {"angular_rate", "acceleration", "unknown"}) {
    nlohmann::json series = nlohmann::json::array();
    std::string unit;
    int color = 0;
    for (const auto& ch : channels) {
      if (ch["quantity"] != quantity) {
        ++color;
        continue;
      }
      const auto* oadev = find_curve(ch, "oadev");
      if (oadev == nullptr) {
        ++color;
        continue;
      }
      unit = ch["unit"].get<std::string>();
      series.push_back(curve_series(*oadev, ch["name"].get<std::string>(), color));
      series.back()["group"] = ch["name"];
      if (ch.contains("model") && !ch["model"].is_null()) {
        series.push_back({{"name", ch["name"].get<std::string>() + " model"},
                          {"group", ch["name"]},
                          {"style", "line"}, {"color", color},
                          {"x", ch["model"]["tau_s"]}, {"y", ch["model"]["adev"]}});
      }
      ++color;
    }
    if (series.size() < 2) continue;  // one channel: its own figure says it all
    const auto& first = channels[0];
    if (first.contains("spec_limits")) {
      for (const auto& line : first["spec_limits"]["lines"]) {
        series.push_back({{"name", line["label"]}, {"style", "limit"}, {"color", 6},
                          {"x", line["tau_s"]}, {"y", line["adev"]}});
      }
    }
    const std::string kind = quantity == "angular_rate" ? "gyros"
                             : quantity == "acceleration" ? "accelerometers" : "channels";
    figures.push_back(
        {{"id", "adev_all_" + (quantity == "angular_rate" ? std::string("gyros")
                               : quantity == "acceleration" ? std::string("accels")
                                                            : std::string("channels"))},
         {"title", "Allan deviation of all " + kind},
         {"caption", "Overlapping Allan deviation of every " + kind.substr(0, kind.size() - 1) +
                         " with " + ci_text(doc) +
                         " confidence bars; solid lines: each fitted noise model; black dotted: "
                         "datasheet limits."},
         {"x_label", "averaging time tau [s]"},
         {"y_label", "Allan deviation [" + unit + "]"},
         {"x_log", true},
         {"y_log", true},
         {"series", std::move(series)}});
  }
  // 2. One figure per channel: curve, fitted model, asymptotes labelled, datasheet limits.
  int color = 0;
  for (const auto& ch : channels) {
    const auto* oadev = find_curve(ch, "oadev");
    const std::string name = ch["name"].get<std::string>();
    if (oadev == nullptr) {
      ++color;
      continue;
    }
    nlohmann::json series = nlohmann::json::array();
    series.push_back(curve_series(*oadev, "oadev " + name, color));
    if (ch.contains("model") && !ch["model"].is_null()) {
      const auto& model = ch["model"];
      series.push_back({{"name", "fitted model"}, {"style", "line"}, {"color", 6},
                        {"x", model["tau_s"]}, {"y", model["adev"]}});
      int term_color = 1;
      for (const auto& t : model["terms"]) {
        series.push_back({{"name", t["label"]}, {"style", "dashed"},
                          {"color", (color + term_color++) % 6},
                          {"x", t["tau_s"]}, {"y", t["adev"]},
                          {"label", {{"x", t["anchor"]["tau_s"]}, {"y", t["anchor"]["adev"]},
                                     {"text", t["label"]}}}});
      }
    }
    if (ch.contains("spec_limits")) {
      for (const auto& line : ch["spec_limits"]["lines"]) {
        series.push_back({{"name", line["label"]}, {"style", "limit"}, {"color", 6},
                          {"x", line["tau_s"]}, {"y", line["adev"]}});
      }
    }
    figures.push_back(
        {{"id", "adev_" + name},
         {"title", "Allan deviation of " + name + " and its noise model"},
         {"caption", "Points: overlapping Allan deviation with " + ci_text(doc) +
                         " confidence bars. Black: the fitted model (paper eq. 5); dashed: each "
                         "identified term's asymptote, labelled with its coefficient, and each "
                         "Gauss-Markov term's own curve (GM1, GM2, ... by correlation time); dotted: "
                         "datasheet limits."},
         {"x_label", "averaging time tau [s]"},
         {"y_label", "Allan deviation [" + ch["unit"].get<std::string>() + "]"},
         {"x_log", true},
         {"y_log", true},
         {"series", std::move(series)}});
    // Other estimators the user asked for, beside oadev.
    if (ch["curves"].size() > 1) {
      nlohmann::json more = nlohmann::json::array();
      int k = 0;
      for (const auto& c : ch["curves"]) {
        if (c["unit"] != ch["unit"]) continue;  // tdev-like curves are angles: another axis
        more.push_back(curve_series(c, c["estimator"].get<std::string>(), k++));
      }
      if (more.size() > 1) {
        figures.push_back(
            {{"id", "curves_" + name},
             {"title", "Deviation estimators of " + name},
             {"caption", "Every requested estimator in the rate unit, with " + ci_text(doc) +
                             " confidence bars."},
             {"x_label", "averaging time tau [s]"},
             {"y_label", "deviation [" + ch["unit"].get<std::string>() + "]"},
             {"x_log", true},
             {"y_log", true},
             {"series", std::move(more)}});
      }
    }
    ++color;
  }
  fused_figure(doc, figures);
  nav_figures(doc, figures);
  budget_figure(doc, figures);
  for (const auto& ch : channels) davar_figure(ch, figures);
  for (auto& f : figures) {
    if (f["x_log"].get<bool>()) set_ranges(f);
  }
  return figures;
}

}  // namespace imunoise::study
