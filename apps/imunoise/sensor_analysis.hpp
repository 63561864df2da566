#pragma once
// The analysis of one sensor record, shared by `fit` and `fleet`: the oadev curve, the noise
// fit and the datasheet verdict as one JSON document (the `fit --format json` document).
//
// analyze_sensor() is the single entry point `fleet` calls per file, so that moving the fleet
// onto the study pipeline's per-record entry point changes only this function.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/deviation.hpp"
#include "imunoise/fit/fit.hpp"
#include "input_options.hpp"

namespace imunoise::cli {

/// The fit of a record's oadev curve (SI, at the fit grid's factors) as the `fit` command
/// reports it. InputError when the curve cannot be fitted (too few taus, degenerate).
struct FitOutcome {
  fit::FitResult result;
  nlohmann::json json;  ///< fit::report_json of the result
};
FitOutcome fit_curve(const PhaseRecord& record, std::size_t n_phase,
                     const std::vector<DevPoint>& oadev_points,
                     const std::vector<std::string>& record_warnings, const fit::FitOptions& options);

struct SensorAnalysisOptions {
  fit::FitOptions fit;
  std::string taus = "octave";  ///< tau grid of the Allan curve
  std::string spec;             ///< --spec NAME|FILE, empty: no datasheet verdict
  bool nav = false;             ///< --nav: the navigation error at the horizon (gyros)
  double nav_hours = 1.0;       ///< the horizon (h), the study's default
};

/// Reads one record and returns its fit document, with "spec_comparison" (null without a
/// spec) and, with options.nav, "nav": the study's navigation error of the sensor's fit at the
/// horizon, {"t_s", "latitude_deg", "models": [{"model", "lat_deg", "path_m", "lon_deg"}]}, or
/// {"t_s", "error": why} when it cannot be computed (not a gyro, no unit, ...). Throws InputError
/// naming the file for anything wrong with the record.
nlohmann::json analyze_sensor(const InputOptions& input, const SensorAnalysisOptions& options);

}  // namespace imunoise::cli
