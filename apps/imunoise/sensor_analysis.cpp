#include "sensor_analysis.hpp"

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/study/study.hpp"
#include "spec_exports.hpp"
#include "study_record.hpp"

namespace imunoise::cli {

FitOutcome fit_curve(const PhaseRecord& record, std::size_t n_phase,
                     const std::vector<DevPoint>& oadev_points,
                     const std::vector<std::string>& record_warnings, const fit::FitOptions& options) {
  const double tau0_s = 1.0 / record.rate_hz;
  FitOutcome out;
  out.result = fit::fit_allan(oadev_points, n_phase, tau0_s, options);
  auto& warnings = out.result.summary.warnings;
  warnings.insert(warnings.begin(), record_warnings.begin(), record_warnings.end());
  if (out.result.summary.termination == fit::Termination::degenerate_input ||
      out.result.summary.termination == fit::Termination::too_few_points) {
    throw InputError(record.source + ": cannot fit a noise model: " + out.result.summary.message);
  }
  out.result.coefficients.quantity = record.rate_unit.quantity == Quantity::acceleration
                                         ? Quantity::acceleration
                                         : Quantity::angular_rate;
  const bool gyro = record.unit_given && record.rate_unit.quantity == Quantity::angular_rate;
  const fit::RecordInfo info{record.source, record.rate_hz, record.n_samples, record.rate_unit,
                             unit_label(record), gyro};
  out.json = fit::report_json(info, options, out.result);
  return out;
}

namespace {

// The study's navigation error of one sensor's fit (the same gyro on all three axes), kept at
// the horizon only: a fleet of thousands keeps one number per model and quantity.
nlohmann::json sensor_navigation(const study::Record& record, const fit::FitResult& result, double hours) {
  if (!study::is_gyro(record) || result.coefficients.quantity != Quantity::angular_rate) {
    return {{"t_s", hours * 3600.0},
            {"error", "not computed: the record is not an angular rate with a unit (--units deg/s, ...)"}};
  }
  study::StudyOptions options;
  options.nav_hours = hours;
  try {
    const auto nav = study::navigation_json(result.coefficients, options);
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

nlohmann::json analyze_sensor(const InputOptions& input, const SensorAnalysisOptions& options) {
  // The study's fit stage (the same checks and fit as `fit` and `analyze`).
  const study::Record record = to_study_record(load_phase(input));
  const fit::FitResult result = study::fit_channel(record, options.fit, parse_tau_grid(options.taus));
  nlohmann::json json = fit::report_json(study::record_info(record), options.fit, result);
  SpecExportOptions spec;
  spec.spec = options.spec;
  json["spec_comparison"] = run_spec_exports(spec, result.coefficients, record.rate_hz);
  if (options.nav) json["nav"] = sensor_navigation(record, result, options.nav_hours);
  return json;
}

}  // namespace imunoise::cli
