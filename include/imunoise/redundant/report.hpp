#pragma once
// The redundant-unit document shared by `imunoise redundant --format json`, Python
// (`imunoise.redundant`, `imunoise.fuse`) and the study report, and the reading of the sensors'
// noise models from `imunoise fit --format json` documents.
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/detection.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/units.hpp"

namespace imunoise::redundant {

/// A sensor's noise model from a fit document: terms Q, N, B, K, R (value, ci_low, ci_high,
/// identified) in the document's "unit", converted to SI. `unit` receives that rate unit
/// ("input unit" documents give a unit with to_si = 1). InputError naming `source` when the
/// document is not a fit document.
SensorModel sensor_model_from_fit_json(const nlohmann::json& document, const std::string& source,
                                       Unit& unit);

/// Reads fit documents (JSON files written by `imunoise fit --format json`), one per sensor.
/// Their units must agree (InputError naming the two files otherwise); `unit` receives it.
std::vector<SensorModel> read_fit_files(std::span<const std::filesystem::path> paths, Unit& unit);

/// The sensors' noise models and the unit of the unit's rates: from `fit_files` (one per sensor
/// of `geometry`, or none) and `units` (the --units text, may be empty). Fits written without a
/// unit are taken in `units`; fits in one unit and `units` another is an InputError, as is a
/// unit that is not an angular rate or a file count that does not match the geometry.
struct ModelsInUnit {
  std::vector<SensorModel> models;
  Unit unit{"rad/s", Quantity::angular_rate, 1.0};
};
ModelsInUnit models_in_unit(std::span<const std::string> fit_files, const std::string& units, const Geometry& geometry);

/// The JSON document (interface.md, "redundant"; docs/redundant.md lists every field):
/// geometry, n_sensors, H, axis_gain, gdop, parity, detectable, isolable, axis_gain_without,
/// gdop_without, false_alarm_per_hour, detection{...}, min_detectable_fault (in `unit`; null
/// without models), min_detectable_fault_window_sigma, and with models: unit, weights,
/// sensors[...], axes[{axis, Q, N, B, K, R}] (each {value, ci_low, ci_high, unit, identified,
/// customary}); with a detection run: faults[{sensor (1-based), t_s (onset), detected_s,
/// isolated, statistic, threshold, max_statistic, alarms}], tests, alarms. Absent numbers are
/// null, never NaN.
nlohmann::json report_json(const Analysis& analysis, const Unit& unit,
                           const DetectionResult* detection = nullptr);

/// The fault list alone (the `faults` array of report_json).
nlohmann::json faults_json(const DetectionResult& detection);

/// The report document of report_json as the text table of `imunoise redundant --format table`.
std::string report_table(const nlohmann::json& report);

}  // namespace imunoise::redundant
