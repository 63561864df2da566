#pragma once
// Measured noise coefficients against a datasheet, term by term, as the paper's conclusion
// does ("bias instability 6 % and 4.5 % above the datasheet; ARW up to 6 % above").
//
// For each term the spec gives (N, B, K) the row holds the measured value in SI, in the
// customary unit and in the spec's own unit (a one-sided noise density is converted with its
// sqrt(2)), the deviation in percent, 100 (measured / spec - 1), and a verdict under the rule
//   pass  <=>  measured <= spec * (1 + tolerance)
// plus where the measured confidence interval lies relative to that limit: entirely below
// (a conclusive pass), entirely above (a conclusive fail) or across it (inconclusive).
//
// With the paper's Table 2 and the TG-100 datasheet the numbers give: gyro 1 B = 5.9e-4 deg/s
// = 2.124 deg/h, +6.2 %; gyro 3 B = 5.8e-4 deg/s = 2.088 deg/h, +4.4 %; gyro 1 N = 8.9e-4
// deg/sqrt(s) = 0.0534 deg/sqrt(h), +6.8 % (the paper rounds to "up to 6 %").
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/noise_coefficients.hpp"
#include "imunoise/spec/spec.hpp"

namespace imunoise {

enum class Verdict {
  pass,            ///< measured <= spec * (1 + tolerance)
  fail,            ///< measured > spec * (1 + tolerance)
  not_identified,  ///< the spec gives the term, the fit could not identify it
  not_in_spec,     ///< the fit identified the term, the spec does not give it
};

/// Where the measured confidence interval lies relative to the pass limit.
enum class CiPosition {
  below,      ///< ci_high <= limit: the pass is conclusive
  above,      ///< ci_low > limit: the fail is conclusive
  straddles,  ///< the interval contains the limit: inconclusive
  unknown,    ///< no interval (NaN bounds), or nothing to compare
};

std::string_view verdict_name(Verdict verdict);          ///< "pass", "fail", "not_identified", ...
std::string_view ci_position_name(CiPosition position);  ///< "below", "above", ...

/// A value in one unit (NaN when not available).
struct ValueInUnit {
  double value = std::numeric_limits<double>::quiet_NaN();
  double ci_low = std::numeric_limits<double>::quiet_NaN();
  double ci_high = std::numeric_limits<double>::quiet_NaN();
  std::string unit;
};

struct ComparisonRow {
  char symbol = 'N';               ///< 'N', 'B' or 'K'
  std::string term;                ///< "random_walk", "bias_instability", "rate_random_walk"
  std::string title;               ///< "angle random walk", "bias instability", ...
  bool identified = false;         ///< the fit identified the term
  ValueInUnit measured_si;         ///< SI (rad/sqrt(s), rad/s, ... or m/s/sqrt(s), ...)
  ValueInUnit measured_customary;  ///< deg/sqrt(h), deg/h, deg/h/sqrt(h) (accel: docs/spec.md)
  ValueInUnit measured_spec_unit;  ///< in the spec's unit and PSD convention; NaN if not in spec
  double spec_value = std::numeric_limits<double>::quiet_NaN();  ///< as written in the spec
  std::string spec_unit;                                         ///< as written
  std::string psd;  ///< the spec's PSD convention name ("not_applicable" if none)
  double spec_si = std::numeric_limits<double>::quiet_NaN();
  double tolerance = 0.0;                                      ///< relative
  double limit_si = std::numeric_limits<double>::quiet_NaN();  ///< spec_si * (1 + tolerance)
  double deviation_percent = std::numeric_limits<double>::quiet_NaN();  ///< 100 (meas/spec - 1)
  Verdict verdict = Verdict::not_in_spec;
  CiPosition ci_position = CiPosition::unknown;
  bool conclusive = false;  ///< the verdict holds over the whole confidence interval
  std::string note;         ///< the fit's note for the term, or why not compared
};

struct SpecComparison {
  std::string spec_name;
  std::string spec_source;
  SensorKind sensor = SensorKind::gyroscope;
  double confidence_level = 0.95;   ///< level of the measured intervals
  std::vector<ComparisonRow> rows;  ///< N, B, K in that order (only terms in spec or fit)
  bool all_pass = false;            ///< every term of the spec was identified and passes
};

/// Compares measured coefficients with a spec. Throws InputError when the spec is for another
/// sensor kind than the coefficients' quantity (a gyro fit against an accelerometer spec).
SpecComparison compare(const NoiseCoefficients& measured, const Spec& spec);

}  // namespace imunoise
