#include "imunoise/export/gtsam.hpp"

#include <cmath>

#include <fmt/core.h>

#include "text.hpp"

namespace imunoise::exports {
namespace {

struct GtsamKey {
  const char* name;
  bool gyro;
  Coefficient NoiseCoefficients::*term;
  const char* symbol;
  const char* unit;
  const char* setter;
};

// GTSAM's covariances are continuous-time PSDs: N^2 for the measurements, K^2 for the walks.
constexpr GtsamKey kKeys[] = {
    {"gyroscopeCovariance", true, &NoiseCoefficients::random_walk, "N", "rad^2/s^2/Hz", "setGyroscopeCovariance"},
    {"accelerometerCovariance", false, &NoiseCoefficients::random_walk, "N", "m^2/s^4/Hz",
     "setAccelerometerCovariance"},
    {"biasOmegaCovariance", true, &NoiseCoefficients::rate_random_walk, "K", "rad^2/s^4/Hz",
     "setBiasOmegaCovariance"},
    {"biasAccCovariance", false, &NoiseCoefficients::rate_random_walk, "K", "m^2/s^6/Hz", "setBiasAccCovariance"},
};

// Integration uncertainty is not a sensor property: GTSAM's examples use 1e-8; stated in the file.
constexpr double kIntegrationCovariance = 1e-8;

detail::Value variance(const ExportModel& m, const GtsamKey& k) {
  return detail::squared(detail::scaled(k.gyro ? m.gyro : m.accel, k.term, 1.0, m.inflation, k.symbol));
}

nlohmann::json diagonal(double v) {
  return nlohmann::json::array({{v, 0.0, 0.0}, {0.0, v, 0.0}, {0.0, 0.0, v}});
}

nlohmann::json coefficient_json(const Coefficient& c) {
  if (!detail::present(c)) return {{"identified", false}, {"note", c.note}};
  nlohmann::json j{{"identified", true}, {"value", c.value}};
  j["ci_low"] = std::isfinite(c.ci_low) ? nlohmann::json(c.ci_low) : nlohmann::json(nullptr);
  j["ci_high"] = std::isfinite(c.ci_high) ? nlohmann::json(c.ci_high) : nlohmann::json(nullptr);
  return j;
}

nlohmann::json sensor_json(const std::optional<SensorModel>& s, bool gyro) {
  if (!s) return nullptr;
  return {{"channels", s->channels},
          {"selection", s->selection},
          {"confidence_level", s->coefficients.confidence_level},
          {"N", coefficient_json(s->coefficients.random_walk)},
          {"N_unit", gyro ? "rad/s/sqrt(Hz)" : "m/s^2/sqrt(Hz)"},
          {"K", coefficient_json(s->coefficients.rate_random_walk)},
          {"K_unit", gyro ? "rad/s^2/sqrt(Hz)" : "m/s^3/sqrt(Hz)"}};
}

}  // namespace

nlohmann::json gtsam_json(const ExportModel& model) {
  check_export_model(model, "--export gtsam");
  nlohmann::json j;
  j["format"] = "imunoise gtsam PreintegrationCombinedParams";
  j["convention"] =
      "continuous-time PSDs (GTSAM divides the measurement covariances by dt and multiplies the "
      "bias ones by dt per integration step): covariance = N^2 I, bias covariance = K^2 I";
  nlohmann::json units;
  nlohmann::json notes = nlohmann::json::object();
  for (const auto& k : kKeys) {
    const auto v = variance(model, k);
    j[k.name] = v.value ? diagonal(*v.value) : nlohmann::json(nullptr);
    units[k.name] = k.unit;
    if (!v.value) notes[k.name] = "NOT MEASURED by imunoise: " + v.why_absent + "; fill in before use";
  }
  j["integrationCovariance"] = diagonal(kIntegrationCovariance);
  units["integrationCovariance"] = "m^2/s^2/Hz (not measured: GTSAM examples' 1e-8)";
  j["units"] = units;
  if (!notes.empty()) j["notes"] = notes;
  j["measured"] = {{"source", model.source},
                   {"rate_hz", model.rate_hz},
                   {"inflation", model.inflation},
                   {"inflation_note", "every covariance = measured x inflation^2"},
                   {"gyroscope", sensor_json(model.gyro, true)},
                   {"accelerometer", sensor_json(model.accel, false)}};
  return j;
}

std::string gtsam_python(const ExportModel& model) {
  check_export_model(model, "--export gtsam");
  std::string out = detail::measured_header(model, "GTSAM PreintegrationCombinedParams (Python)", "#");
  out +=
      "# Continuous-time PSDs: GTSAM divides gyroscope/accelerometerCovariance by dt and multiplies\n"
      "# biasOmega/biasAccCovariance by dt at each step (gtsam/navigation/CombinedImuFactor.cpp).\n"
      "import numpy as np\n"
      "import gtsam\n\n"
      "params = gtsam.PreintegrationCombinedParams.MakeSharedU(9.81)  # z up; use MakeSharedD for NED\n";
  for (const auto& k : kKeys) {
    const auto v = variance(model, k);
    if (v.value) {
      out += fmt::format("params.{}(np.eye(3) * {})  # {} = {}^2{}\n", k.setter, detail::number(*v.value), k.unit,
                         k.symbol, detail::interval_text(v));
    } else {
      out += fmt::format(
          "# params.{}(np.eye(3) * FILL_IN)  # {} -- NOT MEASURED by imunoise: {}\n"
          "FILL_IN_{}  # stops here with a NameError until the value above is filled in\n",
          k.setter, k.unit, v.why_absent, k.name);
    }
  }
  out += fmt::format("params.setIntegrationCovariance(np.eye(3) * {})  # not measured: GTSAM examples' value\n",
                     detail::number(kIntegrationCovariance));
  return out;
}

}  // namespace imunoise::exports
