#include "imunoise/fleet/fleet.hpp"

#include <cmath>
#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/fleet/statistics.hpp"

namespace imunoise::fleet {
namespace {

const char* const kTerms[] = {"Q", "N", "B", "K", "R"};

bool identified_value(const nlohmann::json& term, double& value) {
  if (!term.is_object() || !term.value("identified", false)) return false;
  const auto& v = term["value"];
  if (!v.is_number()) return false;
  value = v.get<double>();
  return std::isfinite(value) && value > 0.0;
}

std::string number(double v) { return fmt::format("{:.6g}", v); }

nlohmann::json quantiles_json(const Quantiles& q) {
  return {{"n", q.n}, {"p05", q.p05}, {"q25", q.q25}, {"median", q.median}, {"q75", q.q75},
          {"p95", q.p95}};
}

void add_flag(nlohmann::json& sensor, const std::string& flag, const std::string& reason) {
  auto& flags = sensor["flags"];
  bool present = false;
  for (const auto& f : flags) present = present || f == flag;
  if (!present) flags.push_back(flag);
  sensor["reasons"].push_back(reason);
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_number(const nlohmann::json& v) {
  return v.is_number() ? fmt::format("{:.9g}", v.get<double>()) : std::string();
}

}  // namespace

nlohmann::json fleet_document(std::span<const SensorOutcome> sensors, const FleetRules& rules) {
  nlohmann::json doc;
  doc["sensors"] = nlohmann::json::array();
  std::size_t analysed = 0;
  nlohmann::json failed = nlohmann::json::array();
  std::set<double> rates;
  for (const auto& s : sensors) {
    nlohmann::json entry{{"file", s.file}, {"fit", s.fit}, {"flags", nlohmann::json::array()},
                         {"reasons", nlohmann::json::array()}};
    if (s.fit.is_null()) {
      entry["error"] = s.error;
      add_flag(entry, "error", s.error);
      failed.push_back({{"file", s.file}, {"error", s.error}});
    } else {
      if (!s.fit.contains("terms")) {
        throw InputError(s.file + ": the fit document has no \"terms\"");
      }
      ++analysed;
      if (s.fit.contains("rate_hz") && s.fit["rate_hz"].is_number()) rates.insert(s.fit["rate_hz"].get<double>());
    }
    doc["sensors"].push_back(std::move(entry));
  }

  // Distributions and outliers, coefficient by coefficient.
  nlohmann::json coefficients = nlohmann::json::object();
  for (const char* name : kTerms) {
    std::vector<double> values;
    std::vector<std::size_t> owner;
    std::string unit;
    std::size_t not_identified = 0, other_unit = 0;
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      const auto& fit = sensors[i].fit;
      if (fit.is_null() || !fit["terms"].contains(name)) continue;
      const auto& term = fit["terms"][name];
      double v = 0.0;
      if (unit.empty()) unit = term.value("unit", std::string());
      if (!identified_value(term, v)) {
        if (term.value("fitted", true)) ++not_identified;
        continue;
      }
      const std::string u = term.value("unit", std::string());
      if (u != unit) {  // a coefficient in another unit cannot share the distribution
        ++other_unit;
        continue;
      }
      values.push_back(v);
      owner.push_back(i);
    }
    if (values.empty() && not_identified == 0) continue;
    nlohmann::json c{{"unit", unit}, {"n_identified", values.size()},
                     {"n_not_identified", not_identified}};
    if (other_unit > 0) c["n_excluded_other_unit"] = other_unit;
    if (!values.empty()) c["distribution"] = quantiles_json(quantiles(values));
    if (values.size() >= rules.min_outlier_sensors) {
      std::vector<double> logs(values.size());
      for (std::size_t k = 0; k < values.size(); ++k) logs[k] = std::log10(values[k]);
      const auto z = robust_z(logs);
      const double median = c["distribution"]["median"].get<double>();
      for (std::size_t k = 0; k < values.size(); ++k) {
        // A score that large can still be estimation noise when the fleet is tighter than one
        // record can resolve: the sensor is an outlier only if its own confidence interval
        // excludes the fleet median too.
        const auto& term = sensors[owner[k]].fit["terms"][name];
        const double lo = term["ci_low"].is_number() ? term["ci_low"].get<double>() : values[k];
        const double hi = term["ci_high"].is_number() ? term["ci_high"].get<double>() : values[k];
        if (std::abs(z[k]) > rules.outlier_z && !(lo <= median && median <= hi)) {
          add_flag(doc["sensors"][owner[k]], "outlier",
                   fmt::format("{} = {} {} is an outlier: robust z = {:+.2f} on log10 (|z| > {:g}), "
                               "and its interval [{}, {}] excludes the fleet median {} {}",
                               name, number(values[k]), unit, z[k], rules.outlier_z, number(lo),
                               number(hi), number(median), unit));
        }
      }
    }
    coefficients[name] = std::move(c);
  }

  // Datasheet verdicts.
  nlohmann::json datasheet = nullptr;
  std::size_t judged = 0, passed = 0;
  std::map<std::string, std::map<std::string, std::size_t>> per_term;
  std::string spec_name;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const auto& fit = sensors[i].fit;
    if (fit.is_null() || !fit.contains("spec_comparison") || fit["spec_comparison"].is_null()) continue;
    const auto& sc = fit["spec_comparison"];
    spec_name = sc.value("spec", std::string());
    ++judged;
    if (sc.value("all_pass", false)) ++passed;
    for (const auto& t : sc["terms"]) {
      const std::string symbol = t.value("symbol", std::string("?"));
      const std::string verdict = t.value("verdict", std::string());
      if (verdict == "not_in_spec") continue;
      ++per_term[symbol][verdict];
      auto& entry = doc["sensors"][i];
      if (verdict == "fail") {
        add_flag(entry, "datasheet_fail",
                 fmt::format("{} fails the datasheet: {} {}, {:+.1f} % against the spec {} {} ({})",
                             symbol, number(t["measured_in_spec_unit"]["value"].get<double>()),
                             t["measured_in_spec_unit"]["unit"].get<std::string>(),
                             t["deviation_percent"].get<double>(),
                             number(t["spec"]["value"].get<double>()),
                             t["spec"]["unit"].get<std::string>(),
                             t.value("conclusive", false) ? "conclusive over the confidence interval"
                                                          : "inconclusive: the interval straddles the limit"));
      } else if (verdict == "not_identified") {
        add_flag(entry, "datasheet_not_identified",
                 symbol + " is in the datasheet but could not be identified from the record");
      }
    }
  }
  if (judged > 0) {
    nlohmann::json terms = nlohmann::json::object();
    for (const auto& [symbol, counts] : per_term) terms[symbol] = counts;
    datasheet = {{"spec", spec_name}, {"n_judged", judged}, {"n_pass", passed},
                 {"pass_rate", static_cast<double>(passed) / static_cast<double>(judged)},
                 {"rule", "a sensor passes when every datasheet term is identified and "
                          "measured <= spec x (1 + tolerance)"},
                 {"terms", terms}};
  }

  // Navigation error at the horizon (fleet --nav): per model and quantity, over the sensors
  // that have it.
  nlohmann::json nav = nullptr;
  {
    std::map<std::string, std::map<std::string, std::vector<double>>> values;  // model -> key -> values
    std::vector<std::string> order;
    double t_s = 0.0, latitude_deg = 0.0;
    std::size_t requested = 0, missing = 0;
    for (const auto& s : sensors) {
      if (s.fit.is_null() || !s.fit.contains("nav")) continue;
      ++requested;
      const auto& n = s.fit["nav"];
      if (n.contains("t_s") && n["t_s"].is_number()) t_s = n["t_s"].get<double>();
      if (!n.contains("models")) {
        ++missing;
        continue;
      }
      t_s = n["t_s"].get<double>();
      latitude_deg = n["latitude_deg"].get<double>();
      for (const auto& m : n["models"]) {
        const std::string model = m["model"].get<std::string>();
        if (std::find(order.begin(), order.end(), model) == order.end()) order.push_back(model);
        for (const char* key : {"lat_deg", "path_m", "lon_deg"}) {
          if (m[key].is_number() && std::isfinite(m[key].get<double>())) values[model][key].push_back(m[key].get<double>());
        }
      }
    }
    if (requested > 0) {
      nlohmann::json models = nlohmann::json::array();
      for (const auto& model : order) {
        nlohmann::json m{{"model", model}};
        for (const char* key : {"lat_deg", "path_m", "lon_deg"}) {
          const auto& v = values[model][key];
          m[key] = v.empty() ? nlohmann::json(nullptr) : quantiles_json(quantiles(v));
        }
        models.push_back(std::move(m));
      }
      nav = {{"t_s", t_s}, {"latitude_deg", latitude_deg}, {"n_sensors", requested - missing},
             {"n_not_computed", missing}, {"models", std::move(models)}};
    }
  }

  nlohmann::json outliers = nlohmann::json::array();
  nlohmann::json flagged = nlohmann::json::array();
  for (const auto& s : doc["sensors"]) {
    for (const auto& f : s["flags"]) {
      if (f == "outlier") outliers.push_back(s["file"]);
    }
    if (!s["flags"].empty()) flagged.push_back(s["file"]);
  }
  doc["summary"] = {
      {"n_files", sensors.size()},
      {"n_analysed", analysed},
      {"n_failed", failed.size()},
      {"failed", failed},
      {"rates_hz", std::vector<double>(rates.begin(), rates.end())},
      {"coefficients", coefficients},
      {"quantiles", "linear interpolation between order statistics (Hyndman-Fan type 7)"},
      {"outlier_rule", {{"score", "robust z = 0.6745 (log10 x - median) / MAD over the fleet's "
                                  "identified values of each coefficient; an outlier has |z| > "
                                  "threshold and a confidence interval that excludes the median"},
                        {"threshold", rules.outlier_z},
                        {"min_sensors", rules.min_outlier_sensors}}},
      {"outliers", outliers},
      {"flagged", flagged},
      {"datasheet", datasheet}};
  if (!nav.is_null()) doc["summary"]["nav"] = std::move(nav);
  return doc;
}

std::string fleet_csv(const nlohmann::json& fleet) {
  const auto& coefficients = fleet["summary"]["coefficients"];
  std::vector<std::string> names;
  std::string header = "file,status,rate_hz,n_samples,unit";
  for (const char* name : kTerms) {
    if (!coefficients.contains(name)) continue;
    names.emplace_back(name);
    const std::string unit = coefficients[name]["unit"].get<std::string>();
    header += "," + csv_field(std::string(name) + " [" + unit + "]") + "," +
              csv_field(std::string(name) + "_ci_low [" + unit + "]") + "," +
              csv_field(std::string(name) + "_ci_high [" + unit + "]") + "," + name + "_identified";
  }
  header += ",datasheet_all_pass";
  std::vector<std::string> nav_models;
  if (fleet["summary"].contains("nav")) {
    for (const auto& m : fleet["summary"]["nav"]["models"]) {
      nav_models.push_back(m["model"].get<std::string>());
      header += ",nav_" + nav_models.back() + "_path_m,nav_" + nav_models.back() + "_lat_deg,nav_" +
                nav_models.back() + "_lon_deg";
    }
  }
  header += ",flags,reasons\n";
  std::string out = header;
  for (const auto& s : fleet["sensors"]) {
    const auto& fit = s["fit"];
    std::vector<std::string> cells{csv_field(s["file"].get<std::string>()),
                                   fit.is_null() ? "error" : "analysed"};
    if (fit.is_null()) {
      cells.insert(cells.end(), {"", "", ""});
      for (std::size_t k = 0; k < names.size(); ++k) cells.insert(cells.end(), {"", "", "", ""});
      cells.emplace_back("");
      for (std::size_t k = 0; k < nav_models.size(); ++k) cells.insert(cells.end(), {"", "", ""});
    } else {
      cells.push_back(csv_number(fit["rate_hz"]));
      cells.push_back(fit["n_samples"].is_number() ? std::to_string(fit["n_samples"].get<std::size_t>()) : "");
      cells.push_back(csv_field(fit.value("unit", std::string())));
      for (const auto& name : names) {
        const auto& t = fit["terms"].contains(name) ? fit["terms"][name] : nlohmann::json();
        const bool same_unit = t.is_object() && t.value("unit", std::string()) ==
                                                    coefficients[name]["unit"].get<std::string>();
        cells.push_back(same_unit ? csv_number(t["value"]) : "");
        cells.push_back(same_unit ? csv_number(t["ci_low"]) : "");
        cells.push_back(same_unit ? csv_number(t["ci_high"]) : "");
        cells.push_back(t.is_object() ? (t.value("identified", false) ? "yes" : "no") : "");
      }
      const auto& sc = fit.contains("spec_comparison") ? fit["spec_comparison"] : nlohmann::json();
      cells.push_back(sc.is_object() ? (sc.value("all_pass", false) ? "yes" : "no") : "");
      for (const auto& model : nav_models) {
        nlohmann::json found;
        if (fit.contains("nav") && fit["nav"].contains("models")) {
          for (const auto& m : fit["nav"]["models"]) {
            if (m["model"] == model) found = m;
          }
        }
        for (const char* key : {"path_m", "lat_deg", "lon_deg"}) {
          cells.push_back(found.is_object() ? csv_number(found[key]) : std::string());
        }
      }
    }
    std::string flags, reasons;
    for (const auto& f : s["flags"]) flags += (flags.empty() ? "" : ";") + f.get<std::string>();
    for (const auto& r : s["reasons"]) reasons += (reasons.empty() ? "" : "; ") + r.get<std::string>();
    cells.push_back(csv_field(flags));
    cells.push_back(csv_field(reasons));
    std::string row;
    for (std::size_t k = 0; k < cells.size(); ++k) row += (k == 0 ? "" : ",") + cells[k];
    out += row + "\n";
  }
  return out;
}

}  // namespace imunoise::fleet
