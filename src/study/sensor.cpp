#include "imunoise/study/sensor.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/study/study.hpp"

namespace imunoise::study {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

double last_in(const std::vector<double>& v, double factor) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double x = v.back() * factor;
  return std::isfinite(x) ? x : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json nav_json(const NavAtHorizon& nav) {
  if (!nav.computed) return {{"t_s", nav.t_s}, {"error", nav.error}};
  nlohmann::json models = nlohmann::json::array();
  for (const auto& m : nav.models) {
    models.push_back({{"model", m.model}, {"lat_deg", number(m.lat_deg)}, {"path_m", number(m.path_m)},
                      {"lon_deg", number(m.lon_deg)}});
  }
  return {{"t_s", nav.t_s}, {"latitude_deg", nav.latitude_deg}, {"models", std::move(models)}};
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
  nav_options.nav_models = "schuler,covariance";  // a fleet keeps one number a model: no simulation
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
  if (const auto nav = nav_at_horizon(options, study)) json["nav"] = nav_json(*nav);
  return json;
}

std::optional<NavAtHorizon> nav_at_horizon(const SensorOptions& options, const SensorStudy& study) {
  if (!study.nav) {
    if (study.nav_error.empty()) return std::nullopt;
    return NavAtHorizon{options.nav_hours * 3600.0, 0.0, false, study.nav_error, {}};
  }
  NavAtHorizon out;
  out.computed = true;
  out.latitude_deg = StudyOptions{}.nav_latitude_deg;
  for (const auto& s : study.nav->models) {
    out.t_s = s.t_s.back();
    out.models.push_back({nav::model_name(s.model), last_in(s.lat_rad, kDeg), last_in(s.north_m, 1.0),
                          study.nav->longitude_defined ? last_in(s.lon_rad, kDeg)
                                                       : std::numeric_limits<double>::quiet_NaN()});
  }
  return out;
}

redundant::SensorModel sensor_model(const Record& record) {
  try {
    return {record.source, fit_channel(record, fit::FitOptions{}, parse_tau_grid("octave")).coefficients};
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + "; give the sensor's fit with --from");
  }
}

}  // namespace imunoise::study
