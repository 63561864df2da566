#pragma once
// A fleet of sensors, one record each: every record loaded and studied (study/sensor.hpp),
// then the fleet's distributions, flags, pass rate and navigation spread (FleetSummary), and
// the fleet document `fleet.json`
//   {"sensors": [{"file", "fit": {...} | null, "flags": [...], "reasons": [...], "error"?}],
//    "summary": {...}}
// and the fleet CSV (one row a sensor) rendered from them. Deterministic: the output depends
// only on the sensors' outcomes and their order, so a parallel run that gathers them in the
// order of the files writes the serial run's bytes.
//
// Per coefficient (Q N B K R, identified values only, in the records' unit): n, 5 %, 25 %,
// 50 %, 75 %, 95 % points (statistics.hpp). Flags and their reasons:
//  - "outlier": |robust z| > outlier_z (3.5, Iglewicz & Hoaglin) on log10 of an identified
//    coefficient, among >= min_outlier_sensors identified values (log: the coefficients of a
//    production batch spread multiplicatively), and the sensor's own confidence interval
//    excludes the fleet median (a fleet tighter than one record can resolve would otherwise
//    flag estimation noise);
//  - "datasheet_fail": a term fails the datasheet (measured > spec (1 + tolerance)); the reason
//    gives the deviation and whether the fail is conclusive over the confidence interval;
//  - "datasheet_not_identified": the datasheet gives a term the record could not identify;
//  - "error": the file could not be analysed (the reason is the error message).
// Pass rate: sensors whose every datasheet term was identified and passes, over the sensors
// analysed against a datasheet.
// Navigation (SensorOptions::nav): summary "nav" {"t_s", "latitude_deg", "n_sensors",
// "n_not_computed", "models": [{"model", "lat_deg", "path_m", "lon_deg": quantiles}]}, and per
// model the CSV columns nav_<model>_path_m, _lat_deg, _lon_deg.
#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/fleet/sensor_summary.hpp"
#include "imunoise/fleet/statistics.hpp"
#include "imunoise/load/load.hpp"

namespace imunoise::fleet {

/// One file's outcome: its summary and its fit document (`study::sensor_json`, written into
/// fleet.json as it is), or the error that stopped its analysis.
struct SensorOutcome {
  std::string file;
  std::optional<SensorSummary> summary;  ///< empty when the analysis failed
  nlohmann::json document;               ///< null when the analysis failed
  std::string error;                     ///< empty when it succeeded
  bool ok() const { return summary.has_value(); }
};

/// Loads `input` and studies it. Any failure (bad file, no fit, out of memory) becomes the
/// outcome's error, prefixed with the file name, so one bad file does not stop a fleet.
SensorOutcome study_file(const load::LoadOptions& input, const study::SensorOptions& options);

struct FleetRules {
  double outlier_z = 3.5;               ///< |robust z| above this flags an outlier
  std::size_t min_outlier_sensors = 5;  ///< fewer identified values: no outlier test
};

struct SensorFlags {
  std::vector<std::string> flags;    ///< each once: error outlier datasheet_fail datasheet_not_identified
  std::vector<std::string> reasons;  ///< one a finding, in the order found
};

struct CoefficientSpread {
  std::string name;  ///< Q N B K R
  std::string unit;  ///< of the first sensor's coefficient; others in another unit are excluded
  std::size_t n_identified = 0;
  std::size_t n_not_identified = 0;
  std::size_t n_excluded_other_unit = 0;
  std::optional<Quantiles> distribution;  ///< of the identified values
};

struct DatasheetTally {
  std::string spec;
  std::size_t n_judged = 0;
  std::size_t n_pass = 0;
  std::map<std::string, std::map<std::string, std::size_t>> verdicts;  ///< symbol -> verdict -> sensors
};

struct NavSpread {
  std::string model;
  std::optional<Quantiles> lat_deg, path_m, lon_deg;
};

struct NavTally {
  double t_s = 0.0;
  double latitude_deg = 0.0;
  std::size_t n_sensors = 0;
  std::size_t n_not_computed = 0;
  std::vector<NavSpread> models;
};

struct FleetSummary {
  FleetRules rules;
  std::vector<SensorFlags> sensors;  ///< one an outcome, in order
  std::size_t n_analysed = 0;
  std::vector<double> rates_hz;      ///< distinct, ascending
  std::vector<CoefficientSpread> coefficients;  ///< Q N B K R, those any sensor has
  std::optional<DatasheetTally> datasheet;
  std::optional<NavTally> nav;
};

FleetSummary summarize_fleet(std::span<const SensorOutcome> sensors, const FleetRules& rules = {});

/// The fleet document (see above).
nlohmann::json fleet_document(std::span<const SensorOutcome> sensors, const FleetSummary& summary);

/// One row a sensor: file, status, rate_hz, n_samples, unit, each coefficient's value and 95 %
/// bounds (the column names carry the unit), identified, datasheet verdict, nav, flags, reasons.
std::string fleet_csv(std::span<const SensorOutcome> sensors, const FleetSummary& summary);

}  // namespace imunoise::fleet
