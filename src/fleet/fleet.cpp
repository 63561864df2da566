#include "imunoise/fleet/fleet.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <set>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::fleet {
namespace {

std::string number(double v) { return fmt::format("{:.6g}", v); }

bool identified_value(const TermSummary& term) {
  return term.identified && std::isfinite(term.value) && term.value > 0.0;
}

void add_flag(SensorFlags& sensor, const std::string& flag, const std::string& reason) {
  if (std::find(sensor.flags.begin(), sensor.flags.end(), flag) == sensor.flags.end()) sensor.flags.push_back(flag);
  sensor.reasons.push_back(reason);
}

// Distribution and outliers of coefficient j over the analysed sensors.
std::optional<CoefficientSpread> spread_of(std::size_t j, std::span<const SensorOutcome> sensors,
                                           FleetSummary& fleet) {
  CoefficientSpread c;
  std::vector<double> values;
  std::vector<std::size_t> owner;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (!sensors[i].ok()) continue;
    const TermSummary& term = sensors[i].summary->terms[j];
    if (c.name.empty()) c.name = term.name;
    if (c.unit.empty()) c.unit = term.unit;
    if (!identified_value(term)) {
      if (term.fitted) ++c.n_not_identified;
      continue;
    }
    if (term.unit != c.unit) {  // a coefficient in another unit cannot share the distribution
      ++c.n_excluded_other_unit;
      continue;
    }
    values.push_back(term.value);
    owner.push_back(i);
  }
  c.n_identified = values.size();
  if (values.empty() && c.n_not_identified == 0) return std::nullopt;
  if (!values.empty()) c.distribution = quantiles(values);
  if (values.size() < fleet.rules.min_outlier_sensors) return c;
  std::vector<double> logs(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) logs[k] = std::log10(values[k]);
  const auto z = robust_z(logs);
  const double median = c.distribution->median;
  for (std::size_t k = 0; k < values.size(); ++k) {
    // A score that large can still be estimation noise when the fleet is tighter than one
    // record can resolve: the sensor is an outlier only if its own confidence interval
    // excludes the fleet median too.
    const TermSummary& term = sensors[owner[k]].summary->terms[j];
    const double lo = std::isfinite(term.ci_low) ? term.ci_low : values[k];
    const double hi = std::isfinite(term.ci_high) ? term.ci_high : values[k];
    if (std::abs(z[k]) > fleet.rules.outlier_z && !(lo <= median && median <= hi)) {
      add_flag(fleet.sensors[owner[k]], "outlier",
               fmt::format("{} = {} {} is an outlier: robust z = {:+.2f} on log10 (|z| > {:g}), "
                           "and its interval [{}, {}] excludes the fleet median {} {}",
                           c.name, number(values[k]), c.unit, z[k], fleet.rules.outlier_z, number(lo),
                           number(hi), number(median), c.unit));
    }
  }
  return c;
}

std::optional<DatasheetTally> datasheet_of(std::span<const SensorOutcome> sensors, FleetSummary& fleet) {
  DatasheetTally tally;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (!sensors[i].ok() || !sensors[i].summary->datasheet) continue;
    const DatasheetSummary& sheet = *sensors[i].summary->datasheet;
    tally.spec = sheet.spec;
    ++tally.n_judged;
    if (sheet.all_pass) ++tally.n_pass;
    for (const auto& t : sheet.terms) {
      if (t.verdict == "not_in_spec") continue;
      ++tally.verdicts[t.symbol][t.verdict];
      if (t.verdict == "fail") {
        add_flag(fleet.sensors[i], "datasheet_fail",
                 fmt::format("{} fails the datasheet: {} {}, {:+.1f} % against the spec {} {} ({})", t.symbol,
                             number(t.measured), t.measured_unit, t.deviation_percent, number(t.spec), t.spec_unit,
                             t.conclusive ? "conclusive over the confidence interval"
                                          : "inconclusive: the interval straddles the limit"));
      } else if (t.verdict == "not_identified") {
        add_flag(fleet.sensors[i], "datasheet_not_identified",
                 t.symbol + " is in the datasheet but could not be identified from the record");
      }
    }
  }
  if (tally.n_judged == 0) return std::nullopt;
  return tally;
}

// Navigation error at the horizon: per model and quantity, over the sensors that have it.
std::optional<NavTally> nav_of(std::span<const SensorOutcome> sensors) {
  NavTally tally;
  std::size_t requested = 0;
  std::map<std::string, std::vector<double>> lat, path, lon;
  std::vector<std::string> order;
  for (const auto& s : sensors) {
    if (!s.ok() || !s.summary->nav) continue;
    ++requested;
    const study::NavAtHorizon& nav = *s.summary->nav;
    tally.t_s = nav.t_s;
    if (!nav.computed) {
      ++tally.n_not_computed;
      continue;
    }
    tally.latitude_deg = nav.latitude_deg;
    for (const auto& m : nav.models) {
      if (std::find(order.begin(), order.end(), m.model) == order.end()) order.push_back(m.model);
      if (std::isfinite(m.lat_deg)) lat[m.model].push_back(m.lat_deg);
      if (std::isfinite(m.path_m)) path[m.model].push_back(m.path_m);
      if (std::isfinite(m.lon_deg)) lon[m.model].push_back(m.lon_deg);
    }
  }
  if (requested == 0) return std::nullopt;
  tally.n_sensors = requested - tally.n_not_computed;
  const auto spread = [](const std::vector<double>& v) {
    return v.empty() ? std::nullopt : std::optional<Quantiles>(quantiles(v));
  };
  for (const auto& model : order) tally.models.push_back({model, spread(lat[model]), spread(path[model]), spread(lon[model])});
  return tally;
}

nlohmann::json quantiles_json(const std::optional<Quantiles>& q) {
  if (!q) return nullptr;
  return {{"n", q->n}, {"p05", q->p05}, {"q25", q->q25}, {"median", q->median}, {"q75", q->q75}, {"p95", q->p95}};
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string(); }

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (std::size_t k = 0; k < items.size(); ++k) out += (k == 0 ? "" : separator) + items[k];
  return out;
}

}  // namespace

SensorOutcome study_file(const load::LoadOptions& input, const study::SensorOptions& options) {
  SensorOutcome outcome;
  outcome.file = input.file;
  try {
    const Record record = load::load(input);
    const study::SensorStudy sensor = study::study_sensor(record, options);
    outcome.summary = summarize(record, options, sensor);
    outcome.document = study::sensor_json(record, options, sensor);
  } catch (const InputError& e) {
    outcome.error = e.what();
  } catch (const std::bad_alloc&) {
    outcome.error = "out of memory";
  } catch (const std::exception& e) {
    outcome.error = std::string("internal error: ") + e.what();
  }
  if (!outcome.error.empty()) {
    outcome.summary.reset();
    outcome.document = nullptr;
    if (outcome.error.rfind(outcome.file, 0) != 0) outcome.error = outcome.file + ": " + outcome.error;
  }
  return outcome;
}

FleetSummary summarize_fleet(std::span<const SensorOutcome> sensors, const FleetRules& rules) {
  FleetSummary fleet;
  fleet.rules = rules;
  fleet.sensors.resize(sensors.size());
  std::set<double> rates;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (!sensors[i].ok()) {
      add_flag(fleet.sensors[i], "error", sensors[i].error);
      continue;
    }
    ++fleet.n_analysed;
    rates.insert(sensors[i].summary->rate_hz);
  }
  fleet.rates_hz.assign(rates.begin(), rates.end());
  for (std::size_t j = 0; j < 5; ++j) {
    if (auto c = spread_of(j, sensors, fleet)) fleet.coefficients.push_back(std::move(*c));
  }
  fleet.datasheet = datasheet_of(sensors, fleet);
  fleet.nav = nav_of(sensors);
  return fleet;
}

nlohmann::json fleet_document(std::span<const SensorOutcome> sensors, const FleetSummary& fleet) {
  nlohmann::json doc;
  doc["sensors"] = nlohmann::json::array();
  nlohmann::json failed = nlohmann::json::array();
  nlohmann::json outliers = nlohmann::json::array();
  nlohmann::json flagged = nlohmann::json::array();
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const auto& s = sensors[i];
    const auto& f = fleet.sensors[i];
    nlohmann::json entry{{"file", s.file}, {"fit", s.ok() ? s.document : nlohmann::json(nullptr)},
                         {"flags", f.flags}, {"reasons", f.reasons}};
    if (!s.ok()) {
      entry["error"] = s.error;
      failed.push_back({{"file", s.file}, {"error", s.error}});
    }
    if (std::find(f.flags.begin(), f.flags.end(), "outlier") != f.flags.end()) outliers.push_back(s.file);
    if (!f.flags.empty()) flagged.push_back(s.file);
    doc["sensors"].push_back(std::move(entry));
  }
  nlohmann::json coefficients = nlohmann::json::object();
  for (const auto& c : fleet.coefficients) {
    nlohmann::json j{{"unit", c.unit}, {"n_identified", c.n_identified}, {"n_not_identified", c.n_not_identified}};
    if (c.n_excluded_other_unit > 0) j["n_excluded_other_unit"] = c.n_excluded_other_unit;
    if (c.distribution) j["distribution"] = quantiles_json(c.distribution);
    coefficients[c.name] = std::move(j);
  }
  nlohmann::json datasheet = nullptr;
  if (const auto& d = fleet.datasheet) {
    datasheet = {{"spec", d->spec}, {"n_judged", d->n_judged}, {"n_pass", d->n_pass},
                 {"pass_rate", static_cast<double>(d->n_pass) / static_cast<double>(d->n_judged)},
                 {"rule", "a sensor passes when every datasheet term is identified and "
                          "measured <= spec x (1 + tolerance)"},
                 {"terms", d->verdicts}};
  }
  doc["summary"] = {
      {"n_files", sensors.size()},
      {"n_analysed", fleet.n_analysed},
      {"n_failed", failed.size()},
      {"failed", failed},
      {"rates_hz", fleet.rates_hz},
      {"coefficients", coefficients},
      {"quantiles", "linear interpolation between order statistics (Hyndman-Fan type 7)"},
      {"outlier_rule", {{"score", "robust z = 0.6745 (log10 x - median) / MAD over the fleet's "
                                  "identified values of each coefficient; an outlier has |z| > "
                                  "threshold and a confidence interval that excludes the median"},
                        {"threshold", fleet.rules.outlier_z},
                        {"min_sensors", fleet.rules.min_outlier_sensors}}},
      {"outliers", outliers},
      {"flagged", flagged},
      {"datasheet", datasheet}};
  if (const auto& n = fleet.nav) {
    nlohmann::json models = nlohmann::json::array();
    for (const auto& m : n->models) {
      models.push_back({{"model", m.model}, {"lat_deg", quantiles_json(m.lat_deg)},
                        {"path_m", quantiles_json(m.path_m)}, {"lon_deg", quantiles_json(m.lon_deg)}});
    }
    doc["summary"]["nav"] = {{"t_s", n->t_s}, {"latitude_deg", n->latitude_deg}, {"n_sensors", n->n_sensors},
                             {"n_not_computed", n->n_not_computed}, {"models", std::move(models)}};
  }
  return doc;
}

std::string fleet_csv(std::span<const SensorOutcome> sensors, const FleetSummary& fleet) {
  std::string out = "file,status,rate_hz,n_samples,unit";
  for (const auto& c : fleet.coefficients) {
    out += "," + csv_field(c.name + " [" + c.unit + "]") + "," + csv_field(c.name + "_ci_low [" + c.unit + "]") +
           "," + csv_field(c.name + "_ci_high [" + c.unit + "]") + "," + c.name + "_identified";
  }
  out += ",datasheet_all_pass";
  std::vector<std::string> nav_models;
  if (fleet.nav) {
    for (const auto& m : fleet.nav->models) {
      nav_models.push_back(m.model);
      out += ",nav_" + m.model + "_path_m,nav_" + m.model + "_lat_deg,nav_" + m.model + "_lon_deg";
    }
  }
  out += ",flags,reasons\n";
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const auto& s = sensors[i];
    std::vector<std::string> cells{csv_field(s.file), s.ok() ? "analysed" : "error"};
    if (!s.ok()) {
      cells.resize(cells.size() + 3 + 4 * fleet.coefficients.size() + 1 + 3 * nav_models.size());
    } else {
      const SensorSummary& summary = *s.summary;
      cells.push_back(csv_number(summary.rate_hz));
      cells.push_back(std::to_string(summary.n_samples));
      cells.push_back(csv_field(summary.unit));
      for (const auto& c : fleet.coefficients) {
        const auto& t = *std::find_if(summary.terms.begin(), summary.terms.end(),
                                      [&](const TermSummary& term) { return term.name == c.name; });
        const bool same_unit = t.unit == c.unit;
        cells.push_back(same_unit ? csv_number(t.value) : "");
        cells.push_back(same_unit ? csv_number(t.ci_low) : "");
        cells.push_back(same_unit ? csv_number(t.ci_high) : "");
        cells.push_back(t.identified ? "yes" : "no");
      }
      cells.push_back(summary.datasheet ? (summary.datasheet->all_pass ? "yes" : "no") : "");
      for (const auto& model : nav_models) {
        const study::NavModelAtHorizon* found = nullptr;
        if (summary.nav) {
          for (const auto& m : summary.nav->models) {
            if (m.model == model) found = &m;
          }
        }
        for (const double v : {found ? found->path_m : NAN, found ? found->lat_deg : NAN, found ? found->lon_deg : NAN}) {
          cells.push_back(csv_number(v));
        }
      }
    }
    cells.push_back(csv_field(joined(fleet.sensors[i].flags, ";")));
    cells.push_back(csv_field(joined(fleet.sensors[i].reasons, "; ")));
    out += joined(cells, ",") + "\n";
  }
  return out;
}

}  // namespace imunoise::fleet
