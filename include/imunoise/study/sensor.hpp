#pragma once
// The study of one sensor record in one call, for callers that study records one at a time
// (the fleet, a file per sensor): the noise-model fit (fit_stage.hpp), the datasheet verdict
// and, on request, the navigation error at the horizon (the same models as run_study).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/fit/fit.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/spec/comparison.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::study {

struct SensorOptions {
  fit::FitOptions fit;
  TauGrid grid;                 ///< tau grid of the fitted Allan curve (octave)
  std::optional<Spec> spec;     ///< datasheet to compare with
  bool nav = false;             ///< the navigation error at the horizon (gyros)
  double nav_hours = 1.0;       ///< the horizon (h), the study's default
};

struct SensorStudy {
  fit::FitResult fit;
  std::optional<SpecComparison> comparison;
  /// The navigation error when asked for (options.nav) and computable; otherwise why not in
  /// nav_error (not a gyro, no unit, ...).
  std::optional<nav::NavResult> nav;
  std::string nav_error;
};

/// The navigation error at the horizon only (a fleet of thousands keeps one number per model
/// and quantity). A number that is not finite is NaN (null in the document).
struct NavModelAtHorizon {
  std::string model;
  double lat_deg = 0.0;
  double path_m = 0.0;
  double lon_deg = 0.0;  ///< NaN where the longitude is undefined (the pole)
};

struct NavAtHorizon {
  double t_s = 0.0;
  double latitude_deg = 0.0;
  bool computed = false;                  ///< false: `error` says why
  std::string error;
  std::vector<NavModelAtHorizon> models;  ///< the study's models, in order
};

/// InputError naming the record when it cannot be fitted.
SensorStudy study_sensor(const Record& record, const SensorOptions& options);

/// The `imunoise fit` document of the sensor with "spec_comparison" (null without a spec) and,
/// when asked for, "nav" at the horizon only (a fleet of thousands keeps one number per model
/// and quantity): {"t_s", "latitude_deg", "models": [{"model", "lat_deg", "path_m",
/// "lon_deg"}]}, or {"t_s", "error": why}.
nlohmann::json sensor_json(const Record& record, const SensorOptions& options, const SensorStudy& study);

/// The "nav" of sensor_json, typed: nullopt when not asked for (options.nav).
std::optional<NavAtHorizon> nav_at_horizon(const SensorOptions& options, const SensorStudy& study);

/// The noise model a redundant unit's fusion weights and fault detector need when no fit
/// documents are given: the record's own fit (fit_channel, default options, octave grid), as
/// `imunoise fit` identifies it. InputError naming the record when it cannot be fitted.
redundant::SensorModel sensor_model(const Record& record);

}  // namespace imunoise::study
