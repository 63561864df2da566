#include "imunoise/study/sensor.hpp"

#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/study/study.hpp"

namespace imunoise::study {
namespace {

// The navigation document at its last time only.
nlohmann::json at_horizon(const nav::NavResult& result, double latitude_deg) {
  const auto nav = nav::report_json(result);
  nlohmann::json models = nlohmann::json::array();
  double t_s = 0.0;
  for (const auto& m : nav["models"]) {
    const std::size_t last = m["t_s"].size() - 1;
    t_s = m["t_s"][last].get<double>();
    models.push_back({{"model", m["model"]}, {"lat_deg", m["lat_deg"][last]},
                      {"path_m", m["path_m"][last]},
                      {"lon_deg", m["lon_deg"].is_array() ? m["lon_deg"][last] : nlohmann::json(nullptr)}});
  }
  return {{"t_s", t_s}, {"latitude_deg", latitude_deg}, {"models", std::move(models)}};
}

}  // namespace

SensorStudy study_sensor(const Record& record, const SensorOptions& options) {
  SensorStudy out;
  out.fit = fit_channel(record, options.fit, options.grid);
  if (options.spec) out.comparison = compare(out.fit.coefficients, *options.spec);
  if (!options.nav) return out;
  if (!is_gyro(record) || out.fit.coefficients.quantity != Quantity::angular_rate) {
    out.nav_error = "not computed: the record is not an angular rate with a unit (--units deg/s, ...)";
    return out;
  }
  StudyOptions nav_options;
  nav_options.nav_hours = options.nav_hours;
  try {
    out.nav = navigation(out.fit.coefficients, nav_options);
  } catch (const InputError& e) {
    out.nav_error = std::string("not computed: ") + e.what();
  }
  return out;
}

nlohmann::json sensor_json(const Record& record, const SensorOptions& options, const SensorStudy& study) {
  nlohmann::json json = fit::report_json(record_info(record), options.fit, study.fit);
  json["spec_comparison"] = study.comparison ? comparison_json(*study.comparison) : nlohmann::json(nullptr);
  if (study.nav) {
    json["nav"] = at_horizon(*study.nav, StudyOptions{}.nav_latitude_deg);
  } else if (!study.nav_error.empty()) {
    json["nav"] = {{"t_s", options.nav_hours * 3600.0}, {"error", study.nav_error}};
  }
  return json;
}

redundant::SensorModel sensor_model(const Record& record) {
  try {
    return {record.source, fit_channel(record, fit::FitOptions{}, parse_tau_grid("octave")).coefficients};
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + "; give the sensor's fit with --from");
  }
}

}  // namespace imunoise::study
