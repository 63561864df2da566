#pragma once
// The fit as the user reads it: coefficients in the record's own unit and in customary gyro
// units, verdicts and notes, the paper's eqs. 1-2, diagnostics. One JSON document, shared by
// the command line (`imunoise fit --format json`) and Python (`imunoise.fit`), plus the
// parsing of the user-facing fit options.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/fit/fit.hpp"
#include "imunoise/noise_coefficients.hpp"
#include "imunoise/units.hpp"

namespace imunoise::fit {

/// What the report says about the record the curve came from.
struct RecordInfo {
  std::string source;       ///< file name, or what the caller calls the data
  double rate_hz = 0.0;
  std::size_t n_samples = 0;
  Unit rate_unit;           ///< unit of the rate samples (to_si converts to SI)
  std::string unit_label;   ///< its name, or "input unit" when none was given
  bool gyro = false;        ///< unit given and an angular rate: customary units are added
};

/// Sets options.terms (and gauss_markov, sinusoid) from a comma list of Q, N, B, K, R, GM and
/// SIN; InputError naming an unknown or empty term.
void parse_terms(std::string_view list, FitOptions& options);

/// The --terms text shared by the command line and Python when the user gives none.
inline constexpr std::string_view kDefaultTerms = "Q,N,B,K";

/// The terms of options.method from the user's list: gmwm takes parse_gmwm_terms (the
/// default list kDefaultTerms means "auto": WVIC selection), the others parse_terms.
void parse_method_terms(std::string_view list, FitOptions& options);

/// "none", "aic" or "bic"; InputError otherwise.
Selection parse_selection(std::string_view name);

/// Unit names of the five coefficients (Q N B K R) for a rate unit label: deg/s -> deg,
/// deg/sqrt(s), deg/s, deg/s/sqrt(s), deg/s^2; a label without "/s" gets "*s"-style names.
std::vector<std::string> coefficient_units(const std::string& rate_label);

/// The customary gyro unit of term j: arcsec, deg/sqrt(h), deg/h, deg/h/sqrt(h), deg/h^2.
const CustomaryUnit& customary_unit(int term);

/// The JSON document of the contract (docs/fit.md): unit, method, level, source, rate_hz,
/// n_samples, terms{Q..R: value, unit, ci_low, ci_high, identified, fitted, estimate, note,
/// dominates_tau_s, customary}, and when fitted GM: a list of {sigma, correlation_time_s, ...}
/// ordered by correlation time (wls: one term, with its test; gmwm: every GM term) and
/// SIN{amplitude, frequency_hz, test}, paper{...}, diagnostics{...}, gmwm{...} (method gmwm). Values in the record's unit;
/// absent numbers (eqs. 1-2 without N or K, non-finite bounds) are null, never NaN.
nlohmann::json report_json(const RecordInfo& record, const FitOptions& options,
                           const FitResult& result);

}  // namespace imunoise::fit
