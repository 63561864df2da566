#include "imunoise/confidence/interval.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Errors become NaN rather than exceptions; arguments are checked before every call anyway.
// In double, not promoted to long double (Boost's default): the quantile is good to a few ulp
// either way, and with every tau of a long record (a million quantiles) the x87 long double
// incomplete gamma was a tenth of the run.
using NoThrowPolicy = boost::math::policies::policy<
    boost::math::policies::domain_error<boost::math::policies::ignore_error>,
    boost::math::policies::overflow_error<boost::math::policies::ignore_error>,
    boost::math::policies::evaluation_error<boost::math::policies::ignore_error>,
    boost::math::policies::promote_double<false>>;

}  // namespace

void validate_confidence_level(double level, const std::string& what) {
  if (std::isfinite(level) && level > 0.0 && level < 1.0) return;
  std::string message = fmt::format(
      "{} {:.10g} is impossible: give a probability strictly between 0 and 1, such as 0.683 (one "
      "sigma, the default) or 0.95",
      what, level);
  if (std::isfinite(level) && level > 1.0 && level < 100.0) {
    message += fmt::format(" (for {:.10g}% write {:.10g})", level, level / 100.0);
  }
  throw InputError(message);
}

double chi2_quantile(double p, double edf) {
  if (!(p > 0.0 && p < 1.0) || !(edf > 0.0) || !std::isfinite(edf)) return kNaN;
  const boost::math::chi_squared_distribution<double, NoThrowPolicy> distribution(edf);
  return boost::math::quantile(distribution, p);
}

ConfidenceInterval chi2_interval(double dev, double edf, double level) {
  validate_confidence_level(level);
  if (!(dev >= 0.0) || !std::isfinite(dev) || !(edf > 0.0)) return {kNaN, kNaN};
  if (std::isinf(edf)) return {dev, dev};
  const double tail = (1.0 - level) / 2.0;
  const double upper = chi2_quantile(1.0 - tail, edf);
  const double lower = chi2_quantile(tail, edf);
  const double low = dev * std::sqrt(edf / upper);
  const double high =
      lower > 0.0 ? dev * std::sqrt(edf / lower) : std::numeric_limits<double>::infinity();
  return {low, high};
}

}  // namespace imunoise
