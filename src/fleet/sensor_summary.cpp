#include "imunoise/fleet/sensor_summary.hpp"

#include "imunoise/fit/report.hpp"
#include "imunoise/spec/comparison.hpp"

namespace imunoise::fleet {

SensorSummary summarize(const Record& record, const study::SensorOptions& options, const study::SensorStudy& study) {
  SensorSummary out;
  out.rate_hz = record.rate_hz;
  out.n_samples = record.n_samples;
  out.unit = unit_label(record);
  // As the fit document writes them: each coefficient in the record's rate unit.
  const double to_unit = record.rate_unit.to_si;
  const auto units = fit::coefficient_units(out.unit);
  for (int j = 0; j < fit::kTermCount; ++j) {
    const auto& c = fit::coefficient(study.fit.coefficients, j);
    auto& t = out.terms[static_cast<std::size_t>(j)];
    t = {fit::term_name(j), units[static_cast<std::size_t>(j)], c.value / to_unit, c.ci_low / to_unit,
         c.ci_high / to_unit, c.identified, study.fit.terms[j].fitted};
  }
  if (study.comparison) {
    DatasheetSummary d{study.comparison->spec_name, study.comparison->all_pass, {}};
    for (const auto& r : study.comparison->rows) {
      d.terms.push_back({std::string(1, r.symbol), std::string(verdict_name(r.verdict)), r.measured_spec_unit.value,
                         r.measured_spec_unit.unit, r.deviation_percent, r.spec_value, r.spec_unit, r.conclusive});
    }
    out.datasheet = std::move(d);
  }
  out.nav = study::nav_at_horizon(options, study);
  return out;
}

}  // namespace imunoise::fleet
