#include "imunoise/redundant/report.hpp"

#include <cmath>
#include <fstream>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"

namespace imunoise::redundant {
namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

const char* kTermNames[5] = {"Q", "N", "B", "K", "R"};

Coefficient& term(NoiseCoefficients& c, int j) {
  switch (j) {
    case 0: return c.quantization;
    case 1: return c.random_walk;
    case 2: return c.bias_instability;
    case 3: return c.rate_random_walk;
    default: return c.rate_ramp;
  }
}

double read_number(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || j[key].is_null()) return std::nan("");
  if (!j[key].is_number()) throw InputError(where + ": '" + key + "' is not a number");
  return j[key].get<double>();
}

nlohmann::json matrix_json(const Matrix& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t r = 0; r < m.rows; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (std::size_t c = 0; c < m.cols; ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

SensorModel sensor_model_from_fit_json(const nlohmann::json& doc, const std::string& source, Unit& unit) {
  if (!doc.is_object() || !doc.contains("terms") || !doc["terms"].is_object() || !doc.contains("unit")) {
    throw InputError(source + ": not a fit document (no 'unit' and 'terms'); write it with "
                              "imunoise fit FILE --format json -o " + source);
  }
  const std::string label = doc["unit"].is_string() ? doc["unit"].get<std::string>() : "";
  if (label == "input unit" || label.empty()) {
    unit = Unit{"input unit", Quantity::angular_rate, 1.0};
  } else {
    try {
      unit = parse_unit(label);
    } catch (const InputError&) {
      throw InputError(source + ": unit '" + label + "' is not a rate unit this tool knows");
    }
    if (unit.quantity != Quantity::angular_rate) {
      throw InputError(source + ": unit '" + label + "' is not an angular rate; the redundant "
                                "unit fuses gyros (fit them with --units deg/s or rad/s)");
    }
  }
  SensorModel model;
  model.source = source;
  model.coefficients.quantity = Quantity::angular_rate;
  if (doc.contains("level") && doc["level"].is_number()) model.coefficients.confidence_level = doc["level"].get<double>();
  const auto& terms = doc["terms"];
  for (int j = 0; j < 5; ++j) {
    if (!terms.contains(kTermNames[j])) continue;
    const auto& t = terms[kTermNames[j]];
    const std::string where = source + ": term " + kTermNames[j];
    Coefficient& c = term(model.coefficients, j);
    const double v = read_number(t, "value", where);
    c.value = std::isfinite(v) ? v * unit.to_si : 0.0;
    c.ci_low = read_number(t, "ci_low", where) * unit.to_si;
    c.ci_high = read_number(t, "ci_high", where) * unit.to_si;
    c.identified = t.contains("identified") && t["identified"].is_boolean() ? t["identified"].get<bool>() : c.value > 0;
    if (c.value < 0) throw InputError(where + ": negative value " + fmt::format("{}", v));
  }
  return model;
}

std::vector<SensorModel> read_fit_files(std::span<const std::filesystem::path> paths, Unit& unit) {
  std::vector<SensorModel> models;
  std::string first_source;
  for (const auto& path : paths) {
    const std::string source = path.string();
    std::ifstream in(path);
    if (!in) throw InputError(source + ": cannot open the fit file; check the path");
    nlohmann::json doc;
    try {
      doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(source + ": not valid JSON (" + e.what() + "); write it with imunoise fit "
                                "FILE --format json");
    }
    if (doc.is_array() && doc.size() == 1) doc = doc[0];
    Unit u;
    models.push_back(sensor_model_from_fit_json(doc, source, u));
    if (models.size() == 1) {
      unit = u;
      first_source = source;
    } else if (u.name != unit.name) {
      throw InputError(fmt::format("{} is in {} but {} is in {}: fit every gyro of the unit in the "
                                   "same unit (--units)", source, u.name, first_source, unit.name));
    }
  }
  return models;
}

ModelsInUnit models_in_unit(std::span<const std::string> fit_files, const std::string& units, const Geometry& geometry) {
  ModelsInUnit out;
  if (!fit_files.empty()) {
    if (fit_files.size() != geometry.size()) {
      throw InputError(fmt::format("--from: {} fit files for the {} sensors of geometry {}; give one "
                                   "per sensing axis, in order", fit_files.size(), geometry.size(), geometry.name));
    }
    std::vector<std::filesystem::path> paths(fit_files.begin(), fit_files.end());
    out.models = read_fit_files(paths, out.unit);
  }
  if (units.empty()) return out;
  const Unit given = parse_unit(units);
  if (given.quantity != Quantity::angular_rate) {
    throw InputError("--units " + units + " is not an angular rate; the recordings are gyro rates (e.g. deg/s)");
  }
  if (!out.models.empty() && given.name != out.unit.name && out.unit.name != "input unit") {
    throw InputError(fmt::format("--units {} but the fits ({}) are in {}: the recordings and the "
                                 "fits must be in the same unit", given.name, fit_files[0], out.unit.name));
  }
  if (out.unit.name == "input unit") {
    for (auto& m : out.models) {  // fits written without a unit: their numbers are in --units
      for (auto* c : {&m.coefficients.quantization, &m.coefficients.random_walk, &m.coefficients.bias_instability,
                      &m.coefficients.rate_random_walk, &m.coefficients.rate_ramp}) {
        c->value *= given.to_si;
        c->ci_low *= given.to_si;
        c->ci_high *= given.to_si;
      }
    }
  }
  out.unit = given;
  return out;
}

nlohmann::json faults_json(const DetectionResult& d) {
  nlohmann::json faults = nlohmann::json::array();
  for (const auto& f : d.faults) {
    nlohmann::json candidates = nlohmann::json::array();
    for (const std::size_t i : f.candidates) candidates.push_back(i + 1);
    faults.push_back({{"sensor", f.sensor + 1}, {"candidates", std::move(candidates)}, {"t_s", f.onset_s}, {"detected_s", f.detected_s},
                      {"isolated", f.isolated}, {"statistic", number(f.statistic)},
                      {"threshold", number(f.threshold)}, {"max_statistic", number(f.max_statistic)},
                      {"alarms", f.alarms}});
  }
  return faults;
}

nlohmann::json report_json(const Analysis& a, const Unit& unit, const DetectionResult* detection) {
  const double f = unit.to_si;
  nlohmann::json j;
  j["geometry"] = a.geometry.name;
  j["n_sensors"] = a.geometry.size();
  j["H"] = matrix_json(a.measurement);
  j["axis_gain"] = a.axis_gain;
  j["gdop"] = a.gdop;
  j["parity"] = matrix_json(a.parity);
  j["detectable"] = a.detectable;
  j["isolable"] = a.isolable;
  nlohmann::json gains_without = nlohmann::json::array(), gdop_without = nlohmann::json::array();
  for (std::size_t i = 0; i < a.geometry.size(); ++i) {
    gains_without.push_back(a.axis_gain_without[i] ? nlohmann::json(*a.axis_gain_without[i]) : nlohmann::json(nullptr));
    gdop_without.push_back(a.gdop_without[i] ? nlohmann::json(*a.gdop_without[i]) : nlohmann::json(nullptr));
  }
  j["axis_gain_without"] = gains_without;
  j["gdop_without"] = gdop_without;
  j["fusion_matrix"] = matrix_json(a.fusion);
  j["weights"] = a.weighted ? "white noise (W = diag(1/N_i^2))" : "equal";
  j["unit"] = unit.name;

  const auto& d = detection ? detection->design : a.detection;
  j["false_alarm_per_hour"] = d.false_alarm_per_hour;
  nlohmann::json det{{"statistic", "chi2 of the whitened parity of (window mean - reference mean)"},
                     {"window_s", d.window_s}, {"reference_s", d.reference_s},
                     {"tests_per_hour", d.tests_per_hour},
                     {"per_test_probability", d.per_test_probability}, {"dof", d.dof},
                     {"threshold", d.dof ? number(d.threshold) : nlohmann::json(nullptr)},
                     {"detection_probability", d.detection_probability},
                     {"noncentrality", d.dof ? number(d.noncentrality) : nlohmann::json(nullptr)}};
  if (!d.sigma_difference_rad_s.empty()) {
    nlohmann::json s = nlohmann::json::array();
    for (const double v : d.sigma_difference_rad_s) s.push_back(v / f);
    det["sigma_difference"] = s;
  }
  j["detection"] = det;
  nlohmann::json mdf = nlohmann::json::array(), mdf_sigma = nlohmann::json::array();
  for (std::size_t i = 0; i < a.geometry.size(); ++i) {
    mdf.push_back(number(a.min_detectable_fault_rad_s[i] / f));
    mdf_sigma.push_back(number(a.min_detectable_fault_window_sigma[i]));
  }
  j["min_detectable_fault"] = mdf;
  j["min_detectable_fault_unit"] = unit.name;
  j["min_detectable_fault_window_sigma"] = mdf_sigma;

  if (a.axes) {
    const auto units = fit::coefficient_units(unit.name);
    const bool gyro = unit.name != "input unit";
    nlohmann::json sensors = nlohmann::json::array();
    for (const auto& s : a.sensors) {
      sensors.push_back({{"source", s.source},
                         {"N", s.coefficients.random_walk.value / f},
                         {"B", s.coefficients.bias_instability.value / f},
                         {"K", s.coefficients.rate_random_walk.value / f}});
    }
    j["sensors"] = sensors;
    nlohmann::json axes = nlohmann::json::array();
    const char* names[3] = {"x", "y", "z"};
    for (std::size_t ax = 0; ax < 3; ++ax) {
      nlohmann::json axis{{"axis", names[ax]}};
      auto coeffs = (*a.axes)[ax];
      for (int t = 0; t < 5; ++t) {
        const Coefficient& c = term(coeffs, t);
        nlohmann::json cj{{"value", number(c.value / f)}, {"ci_low", number(c.ci_low / f)},
                          {"ci_high", number(c.ci_high / f)}, {"unit", units[static_cast<std::size_t>(t)]},
                          {"identified", c.identified}};
        if (gyro) {
          const auto& cu = fit::customary_unit(t);
          cj["customary"] = {{"value", number(c.value / cu.to_si)}, {"unit", cu.name}};
        }
        axis[kTermNames[t]] = cj;
      }
      axes.push_back(axis);
    }
    j["axes"] = axes;
  }
  if (detection) {
    j["faults"] = faults_json(*detection);
    j["tests"] = detection->tests;
    j["alarms"] = detection->alarms;
    j["max_statistic"] = number(detection->max_statistic);
    nlohmann::json excluded = nlohmann::json::array();
    for (const auto i : detection->excluded) excluded.push_back(i + 1);
    j["excluded_sensors"] = excluded;
    j["detection"]["window_samples"] = detection->window_samples;
    j["detection"]["rate_hz"] = detection->rate_hz;
  }
  nlohmann::json notes = a.geometry.notes;
  for (const auto& n : a.notes) notes.push_back(n);
  if (detection && detection->tests == 0 && detection->design.dof > 0) {
    notes.push_back(fmt::format("no detection test was made: the record ({:.6g} s) is shorter than "
                                "the reference plus one window ({:.6g} s); shorten --reference",
                                static_cast<double>(detection->samples) / detection->rate_hz,
                                detection->design.reference_s + detection->design.window_s));
  }
  j["notes"] = notes;
  return j;
}

namespace {

std::string table_cell(const nlohmann::json& v, const char* fmt_spec = "{:.4g}") {
  return v.is_number() ? fmt::format(fmt::runtime(fmt_spec), v.get<double>()) : std::string("-");
}

}  // namespace

std::string report_table(const nlohmann::json& j) {
  std::string out = fmt::format("# redundant unit: {} ({} sensors); fusion weights {}\n",
                                j["geometry"].get<std::string>(), j["n_sensors"].get<std::size_t>(),
                                j["weights"].get<std::string>());
  out += fmt::format("axis gain (fused noise / one sensor's): x {:.4f}  y {:.4f}  z {:.4f}   GDOP {:.4f}\n",
                     j["axis_gain"][0].get<double>(), j["axis_gain"][1].get<double>(),
                     j["axis_gain"][2].get<double>(), j["gdop"].get<double>());
  out += fmt::format("parity space: {} row(s); detectable {}, isolable {}\n", j["parity"].size(),
                     j["detectable"].get<bool>() ? "yes" : "no", j["isolable"].get<bool>() ? "yes" : "no");
  for (const auto& row : j["parity"]) {
    std::string r;
    for (const auto& v : row) r += fmt::format(" {:+.4f}", v.get<double>());
    out += "  V:" + r + "\n";
  }
  out += fmt::format("{:<7} {:>10} {:>18} {:>14}\n", "sensor", "GDOP w/o", "min detect. fault", "(window sigma)");
  for (std::size_t i = 0; i < j["gdop_without"].size(); ++i) {
    out += fmt::format("{:<7} {:>10} {:>18} {:>14}\n", i + 1, table_cell(j["gdop_without"][i]),
                       table_cell(j["min_detectable_fault"][i]) + " " + j["min_detectable_fault_unit"].get<std::string>(),
                       table_cell(j["min_detectable_fault_window_sigma"][i]));
  }
  const auto& d = j["detection"];
  out += fmt::format("# detection: {} s window vs {} s reference, {}/h false alarms = {:.3g} per test, "
                     "chi2({}) threshold {}\n", table_cell(d["window_s"]), table_cell(d["reference_s"]),
                     table_cell(j["false_alarm_per_hour"]), d["per_test_probability"].get<double>(),
                     d["dof"].get<std::size_t>(), table_cell(d["threshold"]));
  if (j.contains("axes")) {
    out += fmt::format("{:<5} {:>12} {:>12} {:>12}  ({})\n", "axis", "N", "B", "K", "customary units");
    for (const auto& a : j["axes"]) {
      out += fmt::format("{:<5} {:>12} {:>12} {:>12}  {} / {} / {}\n", a["axis"].get<std::string>(),
                         table_cell(a["N"]["value"]), table_cell(a["B"]["value"]), table_cell(a["K"]["value"]),
                         a["N"]["unit"].get<std::string>(), a["B"]["unit"].get<std::string>(),
                         a["K"]["unit"].get<std::string>());
    }
  }
  if (j.contains("faults")) {
    out += fmt::format("# {} tests, {} alarms, {} fault(s)\n", j["tests"].get<std::size_t>(),
                       j["alarms"].get<std::size_t>(), j["faults"].size());
    for (const auto& f : j["faults"]) {
      out += fmt::format("fault: sensor {} at t = {:.3f} s (detected {:.3f} s), isolated {}, T = {:.4g} > {:.4g}\n",
                         f["sensor"].get<std::size_t>(), f["t_s"].get<double>(), f["detected_s"].get<double>(),
                         f["isolated"].get<bool>() ? "yes" : "no", f["statistic"].get<double>(),
                         f["threshold"].get<double>());
    }
  }
  for (const auto& n : j["notes"]) out += "# note: " + n.get<std::string>() + "\n";
  return out;
}

}  // namespace imunoise::redundant
