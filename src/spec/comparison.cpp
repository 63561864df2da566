#include "imunoise/spec/comparison.hpp"

#include <cmath>
#include <optional>

#include "imunoise/error.hpp"

namespace imunoise {

std::string_view verdict_name(Verdict verdict) {
  switch (verdict) {
    case Verdict::pass:
      return "pass";
    case Verdict::fail:
      return "fail";
    case Verdict::not_identified:
      return "not_identified";
    case Verdict::not_in_spec:
      break;
  }
  return "not_in_spec";
}

std::string_view ci_position_name(CiPosition position) {
  switch (position) {
    case CiPosition::below:
      return "below";
    case CiPosition::above:
      return "above";
    case CiPosition::straddles:
      return "straddles";
    case CiPosition::unknown:
      break;
  }
  return "unknown";
}

namespace {

struct TermInfo {
  char symbol;
  const char* key;
  const char* gyro_title;
  const char* accel_title;
  // Customary units: gyro from units.hpp; accelerometer ones documented in docs/spec.md.
  std::string_view gyro_unit;
  double gyro_to_si;
  std::string_view accel_unit;
  double accel_to_si;
};

constexpr double ug = units::g_to_m_per_s2 * 1e-6;

constexpr TermInfo kTerms[] = {
    {'N', "random_walk", "angle random walk", "velocity random walk", customary_gyro_N.name,
     customary_gyro_N.to_si, "m/s/sqrt(h)", 1.0 / units::sqrt_h_to_sqrt_s},
    {'B', "bias_instability", "bias instability", "bias instability", customary_gyro_B.name,
     customary_gyro_B.to_si, "ug", ug},
    {'K', "rate_random_walk", "rate random walk", "acceleration random walk", customary_gyro_K.name,
     customary_gyro_K.to_si, "ug/sqrt(h)", ug / units::sqrt_h_to_sqrt_s},
};

ValueInUnit scaled(const Coefficient& c, double to_si, std::string unit) {
  ValueInUnit v;
  v.value = c.value / to_si;
  v.ci_low = c.ci_low / to_si;
  v.ci_high = c.ci_high / to_si;
  v.unit = std::move(unit);
  return v;
}

}  // namespace

SpecComparison compare(const NoiseCoefficients& measured, const Spec& spec) {
  const Quantity expected = sensor_quantity(spec.sensor);
  if (measured.quantity != expected) {
    throw InputError("spec '" + spec.name + "' is for a " +
                     std::string(sensor_kind_name(spec.sensor)) + " but the coefficients are of " +
                     std::string(quantity_name(measured.quantity)) +
                     "; fix: compare with a spec of the same sensor kind (sensor: in the file)");
  }
  const bool gyro = spec.sensor == SensorKind::gyroscope;
  const std::string si_names[] = {
      std::string(gyro ? "rad/sqrt(s)" : "m/s/sqrt(s)"),
      std::string(gyro ? "rad/s" : "m/s^2"),
      std::string(gyro ? "rad/s/sqrt(s)" : "m/s^2/sqrt(s)"),
  };
  const Coefficient* coefficients[] = {&measured.random_walk, &measured.bias_instability,
                                       &measured.rate_random_walk};
  const std::optional<SpecTerm>* limits[] = {&spec.random_walk, &spec.bias_instability,
                                             &spec.rate_random_walk};

  SpecComparison result;
  result.spec_name = spec.name;
  result.spec_source = spec.source;
  result.sensor = spec.sensor;
  result.confidence_level = measured.confidence_level;
  bool all_pass = true;
  bool any_in_spec = false;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& info = kTerms[i];
    const Coefficient& c = *coefficients[i];
    const auto& limit = *limits[i];
    if (!limit && !c.identified) continue;
    ComparisonRow row;
    row.symbol = info.symbol;
    row.term = info.key;
    row.title = gyro ? info.gyro_title : info.accel_title;
    row.identified = c.identified;
    row.note = c.note;
    row.measured_si = scaled(c, 1.0, si_names[i]);
    row.measured_customary = gyro ? scaled(c, info.gyro_to_si, std::string(info.gyro_unit))
                                  : scaled(c, info.accel_to_si, std::string(info.accel_unit));
    if (!c.identified) {
      // The fit reports 0 for a term it could not identify: do not present it as a value.
      row.measured_si.value = row.measured_customary.value =
          std::numeric_limits<double>::quiet_NaN();
    }
    if (!limit) {
      row.verdict = Verdict::not_in_spec;
      if (row.note.empty()) row.note = "the spec does not rate this term";
      result.rows.push_back(std::move(row));
      continue;
    }
    any_in_spec = true;
    row.spec_value = limit->value;
    row.spec_unit = limit->unit;
    row.psd = std::string(psd_convention_name(limit->psd));
    row.spec_si = limit->value_si;
    row.tolerance = limit->tolerance;
    row.limit_si = limit->value_si * (1.0 + limit->tolerance);
    row.measured_spec_unit = scaled(c, limit->to_si, limit->unit);
    if (!c.identified) {
      row.measured_spec_unit.value = std::numeric_limits<double>::quiet_NaN();
      row.verdict = Verdict::not_identified;
      all_pass = false;
      if (row.note.empty()) row.note = "the fit could not identify this term";
      result.rows.push_back(std::move(row));
      continue;
    }
    row.deviation_percent = 100.0 * (c.value / limit->value_si - 1.0);
    row.verdict = c.value <= row.limit_si ? Verdict::pass : Verdict::fail;
    if (row.verdict == Verdict::fail) all_pass = false;
    if (std::isfinite(c.ci_low) && std::isfinite(c.ci_high)) {
      if (c.ci_high <= row.limit_si) {
        row.ci_position = CiPosition::below;
      } else if (c.ci_low > row.limit_si) {
        row.ci_position = CiPosition::above;
      } else {
        row.ci_position = CiPosition::straddles;
      }
    }
    row.conclusive = (row.verdict == Verdict::pass && row.ci_position == CiPosition::below) ||
                     (row.verdict == Verdict::fail && row.ci_position == CiPosition::above);
    result.rows.push_back(std::move(row));
  }
  result.all_pass = all_pass && any_in_spec;
  return result;
}

}  // namespace imunoise
