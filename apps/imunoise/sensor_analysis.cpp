#include "sensor_analysis.hpp"

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "spec_exports.hpp"

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
  const PhaseRecord record = load_phase(input);
  const double tau0_s = 1.0 / record.rate_hz;
  const auto warnings = fit::record_warnings(record.phase_si, tau0_s);
  if (fit::is_constant_record(record.phase_si, tau0_s)) {
    throw InputError(record.source + ": the rate is constant (all-zero or a fixed value): there is "
                     "no noise to identify; check --column and the file");
  }
  const auto factors = estimator_averaging_factors(Estimator::oadev, parse_tau_grid(options.taus),
                                                   record.rate_hz, record.phase_si.size());
  const auto points = oadev(record.phase_si, tau0_s, factors);
  FitOutcome out = fit_curve(record, record.phase_si.size(), points, warnings, options.fit);
  SpecExportOptions spec;
  spec.spec = options.spec;
  out.json["spec_comparison"] = run_spec_exports(spec, out.result.coefficients, record.rate_hz);
  return out.json;
}

}  // namespace imunoise::cli
