#pragma once
// GTSAM PreintegrationCombinedParams: gyroscopeCovariance = N^2 I (rad^2/s^2/Hz),
// accelerometerCovariance = N_a^2 I (m^2/s^4/Hz), biasOmegaCovariance = K^2 I (rad^2/s^4/Hz),
// biasAccCovariance = K_a^2 I (m^2/s^6/Hz): continuous-time PSDs. GTSAM divides the
// measurement covariances by dt and multiplies the bias ones by dt at each integration step
// (gtsam/navigation/CombinedImuFactor.cpp, ImuFactor.cpp; PreintegrationCombinedParams.h
// calls them continuous-time covariances).
#include <string>

#include <nlohmann/json.hpp>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// {"format": "imunoise gtsam PreintegrationCombinedParams", "gyroscopeCovariance": 3x3 or
///  null, "accelerometerCovariance", "biasOmegaCovariance", "biasAccCovariance",
///  "integrationCovariance" (a small default, stated), "units": {...}, "measured": {...}}.
/// Absent terms are null with a note. Throws InputError without any sensor.
nlohmann::json gtsam_json(const ExportModel& model);

/// A Python snippet that builds gtsam.PreintegrationCombinedParams with those values
/// (absent terms: a commented line that stops with a NameError until filled in).
std::string gtsam_python(const ExportModel& model);

}  // namespace imunoise::exports
