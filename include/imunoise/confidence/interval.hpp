#pragma once
// Chi-squared confidence interval of a deviation from its equivalent degrees of freedom.
//
// With s^2 ~ sigma^2 chi^2(edf) / edf, the two-sided interval at confidence `level` is
//   sigma_low  = s sqrt(edf / chi2_quantile((1 + level) / 2, edf)),
//   sigma_high = s sqrt(edf / chi2_quantile((1 - level) / 2, edf))
// (NIST SP 1065 eq. 45; Stable32's "min sigma" / "max sigma"). Quantiles come from Boost.Math
// (chi_squared_distribution, relative accuracy ~1e-15 for edf from 1e-3 to 1e12).
//
// Note on Stable32: for large EDF (hundreds) Stable32's 68.3% bounds are those of an exact
// chi-squared interval at level 0.680 (2-3e-4 narrower); at small EDF they agree with 0.683.
// We use the exact quantile at the level asked for (docs/confidence.md).
#include <string>

namespace imunoise {

/// Default confidence level, Stable32's: 68.3% (one sigma).
inline constexpr double kDefaultConfidenceLevel = 0.683;

/// Bounds of a deviation (same unit as the deviation).
struct ConfidenceInterval {
  double low;
  double high;
};

/// Throws InputError unless 0 < level < 1 (a probability, not a percentage); `what` names the
/// argument in the message (e.g. "--ci").
void validate_confidence_level(double level, const std::string& what = "confidence level");

/// Two-sided chi-squared interval of deviation `dev` with `edf` degrees of freedom at `level`.
/// Throws InputError for an impossible level. Numerical outcomes are not errors: a NaN,
/// negative or infinite dev, or an edf that is NaN or <= 0, gives {NaN, NaN}; edf = +infinity
/// gives {dev, dev}.
ConfidenceInterval chi2_interval(double dev, double edf, double level = kDefaultConfidenceLevel);

/// The p-quantile of the chi-squared distribution with `edf` degrees of freedom (Boost.Math);
/// NaN when p is outside (0, 1) or edf is not positive and finite.
double chi2_quantile(double p, double edf);

}  // namespace imunoise
