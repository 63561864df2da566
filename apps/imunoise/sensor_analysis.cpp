#include "sensor_analysis.hpp"

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/study/fit_stage.hpp"
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

nlohmann::json analyze_sensor(const InputOptions& input, const SensorAnalysisOptions& options) {
  // The study's fit stage (the same checks and fit as `fit` and `analyze`).
  const study::Record record = to_study_record(load_phase(input));
  const fit::FitResult result = study::fit_channel(record, options.fit, parse_tau_grid(options.taus));
  nlohmann::json json = fit::report_json(study::record_info(record), options.fit, result);
  SpecExportOptions spec;
  spec.spec = options.spec;
  json["spec_comparison"] = run_spec_exports(spec, result.coefficients, record.rate_hz);
  return json;
}

}  // namespace imunoise::cli
