#include "imunoise/study/sensor.hpp"

#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/study/study.hpp"

namespace imunoise::study {
namespace {

// The study's navigation error of one sensor's fit (the same gyro on all three axes), kept at
// the horizon only: a fleet of thousands keeps one number per model and quantity.
nlohmann::json navigation_at_horizon(const Record& record, const fit::FitResult& result, double hours) {
  if (!is_gyro(record) || result.coefficients.quantity != Quantity::angular_rate) {
    return {{"t_s", hours * 3600.0},
            {"error", "not computed: the record is not an angular rate with a unit (--units deg/s, ...)"}};
  }
  StudyOptions options;
  options.nav_hours = hours;
  try {
    const auto nav = navigation_json(result.coefficients, options);
    nlohmann::json models = nlohmann::json::array();
    double t_s = 0.0;
    for (const auto& m : nav["models"]) {
      const std::size_t last = m["t_s"].size() - 1;
      t_s = m["t_s"][last].get<double>();
      models.push_back({{"model", m["model"]}, {"lat_deg", m["lat_deg"][last]},
                        {"path_m", m["path_m"][last]},
                        {"lon_deg", m["lon_deg"].is_array() ? m["lon_deg"][last] : nlohmann::json(nullptr)}});
    }
    return {{"t_s", t_s}, {"latitude_deg", options.nav_latitude_deg}, {"models", std::move(models)}};
  } catch (const InputError& e) {
    return {{"t_s", hours * 3600.0}, {"error", std::string("not computed: ") + e.what()}};
  }
}

}  // namespace

SensorStudy study_sensor(const Record& record, const SensorOptions& options) {
  SensorStudy out;
  out.fit = fit_channel(record, options.fit, options.grid);
  if (options.spec) out.comparison = compare(out.fit.coefficients, *options.spec);
  if (options.nav) out.nav = navigation_at_horizon(record, out.fit, options.nav_hours);
  return out;
}

nlohmann::json sensor_json(const Record& record, const SensorOptions& options, const SensorStudy& study) {
  nlohmann::json json = fit::report_json(record_info(record), options.fit, study.fit);
  json["spec_comparison"] = study.comparison ? comparison_json(*study.comparison) : nlohmann::json(nullptr);
  if (!study.nav.is_null()) json["nav"] = study.nav;
  return json;
}

}  // namespace imunoise::study
