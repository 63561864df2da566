#pragma once
// A fleet of sensors: from the per-sensor fit documents (the `fit --format json` document with
// its "spec_comparison") to the fleet document `fleet.json`
//   {"sensors": [{"file", "fit": {...} | null, "flags": [...], "reasons": [...], "error"?}],
//    "summary": {...}}
// and the fleet CSV (one row a sensor). Deterministic: the output depends only on the
// sensors' documents and their order, so a parallel run that gathers them in the order of the
// files writes the serial run's bytes.
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
// Navigation (fleet --nav: each fit document has "nav" {"t_s", "latitude_deg", "models":
// [{"model", "lat_deg", "path_m", "lon_deg"}]} or {"error"}): summary "nav" {"t_s",
// "latitude_deg", "n_sensors", "n_not_computed", "models": [{"model", "lat_deg", "path_m",
// "lon_deg": quantiles}]}, and per model the CSV columns nav_<model>_path_m, _lat_deg, _lon_deg.
#include <cstddef>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

namespace imunoise::fleet {

/// One file's outcome: its fit document, or the error that stopped its analysis.
struct SensorOutcome {
  std::string file;
  nlohmann::json fit;  ///< null when the analysis failed
  std::string error;   ///< empty when it succeeded
};

struct FleetRules {
  double outlier_z = 3.5;               ///< |robust z| above this flags an outlier
  std::size_t min_outlier_sensors = 5;  ///< fewer identified values: no outlier test
};

/// The fleet document (see above). InputError when a fit document lacks "terms".
nlohmann::json fleet_document(std::span<const SensorOutcome> sensors, const FleetRules& rules = {});

/// One row a sensor: file, status, rate_hz, n_samples, unit, each coefficient's value and 95 %
/// bounds (the column names carry the unit), identified, datasheet verdict, flags, reasons.
std::string fleet_csv(const nlohmann::json& fleet);

}  // namespace imunoise::fleet
