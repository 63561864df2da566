#include "imunoise/study/figures.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
                         "identified term's asymptote, labelled with its coefficient; dotted: "
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
  for (auto& f : figures) set_ranges(f);
  return figures;
}

}  // namespace imunoise::study
