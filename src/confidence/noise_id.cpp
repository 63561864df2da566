#include "imunoise/confidence/noise_id.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/error.hpp"
#include "../core/parallel.hpp"  // the library's fork-join helper
#include "power_law_model.hpp"

namespace imunoise {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t decimated_count(std::size_t n_phase, std::size_t m) {
  return n_phase == 0 ? 0 : (n_phase - 1) / m + 1;
}

// The total family and Theo1 identify noise as their finite-difference proxies do (edf.hpp).
int family_d(Estimator estimator) {
  const auto proxy = finite_difference_proxy(estimator);
  if (!proxy) return 0;
  const auto v = difference_variance(*proxy);
  return v ? v->d : 0;
}

int lowest_alpha(int d) { return std::max(kMinNoiseAlpha, 2 - 2 * d); }

// Identification reads at most the first 2^20 decimated points: the lag-1 estimate's
// standard error there is ~1/sqrt(2^20) = 1e-3, far inside the 1/4 decision margin, and a
// record of 1e8 samples is neither copied nor read in full for every tau.
constexpr std::size_t kMaxIdentificationPoints = std::size_t{1} << 20;

// The d-th difference of the phase decimated by m, z_d[i] = sum_j (-1)^(d-j) C(d,j) x[(i+j)m],
// formed on the fly (long double: exact for the small binomial weights) instead of stored.
class DecimatedDifference {
 public:
  DecimatedDifference(std::span<const double> phase, std::size_t m, std::size_t points, int d)
      : phase_(phase), m_(m), count_(points - static_cast<std::size_t>(d)) {
    long double c = 1.0L;  // C(d, j) with alternating sign, highest index last
    for (int j = 0; j <= d; ++j) {
      weights_.push_back(((d - j) % 2 == 0 ? 1.0L : -1.0L) * c);
      c = c * (d - j) / (j + 1);
    }
  }
  [[nodiscard]] std::size_t size() const { return count_; }
  [[nodiscard]] long double operator[](std::size_t i) const {
    long double z = 0.0L;
    for (std::size_t j = 0; j < weights_.size(); ++j) z += weights_[j] * phase_[(i + j) * m_];
    return z;
  }

 private:
  std::span<const double> phase_;
  std::size_t m_;
  std::size_t count_;
  std::vector<long double> weights_;
};

// Lag-1 autocorrelation about the mean (two passes: mean, then centred sums).
double lag1_of(const DecimatedDifference& z) {
  const std::size_t n = z.size();
  if (n < 3) return kNaN;
  long double mean = 0.0L;
  for (std::size_t i = 0; i < n; ++i) mean += z[i];
  mean /= static_cast<long double>(n);
  long double num = 0.0L;
  long double den = 0.0L;
  long double previous = z[0] - mean;
  den += previous * previous;
  for (std::size_t i = 1; i < n; ++i) {
    const long double a = z[i] - mean;
    den += a * a;
    num += previous * a;
    previous = a;
  }
  if (!(den > 0.0L) || !std::isfinite(static_cast<double>(den))) return kNaN;
  return static_cast<double>(num / den);
}

// The lag-1 procedure on phase decimated by m: the differencing order d where it stopped and
// delta = r1 / (1 + r1) there. delta is NaN when the data are too short or degenerate.
struct Lag1Stage {
  double delta = kNaN;
  int d = 0;
};

Lag1Stage lag1_stage(std::span<const double> phase, std::size_t m, int d_max) {
  Lag1Stage stage;
  if (m == 0 || d_max < 0) return stage;
  const std::size_t points = std::min(decimated_count(phase.size(), m), kMaxIdentificationPoints);
  if (points < static_cast<std::size_t>(d_max) + 3) return stage;
  for (int d = 0;; ++d) {
    const double r1 = lag1_of(DecimatedDifference(phase, m, points, d));
    if (std::isnan(r1)) return stage;
    const double delta = r1 / (1.0 + r1);
    if (delta < 0.25 || d >= d_max) {
      stage.delta = delta;
      stage.d = d;
      return stage;
    }
  }
}

// Expected delta at differencing order d for noise alpha, phase decimated by m, in the
// Greenhall-Riley model (phase samples are tau0-averages): rho(1) of the d-th differences.
double model_delta(int alpha, int d, std::size_t m) {
  const double F = static_cast<double>(m);
  const double r1 = detail::power_law_sz(1.0, F, alpha, d) / detail::power_law_sz(0.0, F, alpha, d);
  return r1 / (1.0 + r1);
}

// Classifies a stopped lag-1 stage. Rounding 2 - 2 (delta + d) (Stable32) puts the boundary
// between the two noise types that stop at order d >= 1, the "flicker" alpha = 3 - 2d and the
// "white" alpha = 2 - 2d, at delta = -1/4: midway between their values for discrete-time
// power-law noise (-1/2 and 0), right at m = 1. At m >= 2 the decimated phase of sampled noise
// has other values (Greenhall-Riley model, phase samples as tau0-averages; flicker FM: -0.20 at
// m = 2 to -0.28 at large m, random-walk FM: 0.23 to 0.20), which rounding misreads (flicker FM
// is taken for random-walk FM in ~25% of cases at m = 4). So at m >= 2 the nearest model value
// wins. In the Hadamard family random-walk FM reaches delta >= 1/4 at d = 2 in ~10% of cases and
// is differenced a third time; its model value there (-0.42 .. -0.50) is a third candidate.
int classify(const Lag1Stage& stage, std::size_t m, int low) {
  const double estimate = 2.0 - 2.0 * (stage.delta + stage.d);
  const int d = stage.d;
  int alpha = static_cast<int>(std::lround(std::clamp(estimate, -8.0, 8.0)));
  if (d >= 1 && m >= 2 && stage.delta >= -0.75) {
    const int highest = d == 3 ? 4 - 2 * d : 3 - 2 * d;
    double best = std::numeric_limits<double>::infinity();
    for (int candidate = 2 - 2 * d; candidate <= highest; ++candidate) {
      const double distance = std::fabs(stage.delta - model_delta(candidate, d, m));
      if (distance < best) {
        best = distance;
        alpha = candidate;
      }
    }
  }
  return std::clamp(alpha, low, 2);
}

std::string too_few_message(Estimator estimator, std::size_t n_phase, std::size_t m) {
  const std::size_t points = decimated_count(n_phase, m);
  return "too few samples for noise identification (" + std::string(estimator_name(estimator)) +
         " at m = " + std::to_string(m) + "): " + std::to_string(n_phase) + " phase points give " +
         std::to_string(points) + " at stride m; the lag-1 autocorrelation needs " +
         std::to_string(kMinLag1AcfPoints) + " and the B1 ratio " +
         std::to_string(kMinB1Averages + 1) +
         "; use a smaller averaging factor or force the noise type (--noise-type)";
}

}  // namespace

std::string_view noise_id_method_name(NoiseIdMethod method) {
  switch (method) {
    case NoiseIdMethod::lag1_acf:
      return "lag1-acf";
    case NoiseIdMethod::b1_ratio:
      return "b1";
    case NoiseIdMethod::b1_rn_ratio:
      return "b1+rn";
    case NoiseIdMethod::forced:
      return "forced";
    case NoiseIdMethod::previous_tau:
      return "previous-tau";
    case NoiseIdMethod::none:
      return "none";
  }
  return "none";
}

double lag1_autocorrelation(std::span<const double> values) {
  const std::size_t n = values.size();
  if (n < 3) return kNaN;
  long double mean = 0.0L;
  for (double v : values) mean += v;
  mean /= static_cast<long double>(n);
  long double num = 0.0L;
  long double den = 0.0L;
  for (std::size_t i = 0; i < n; ++i) {
    const long double a = values[i] - mean;
    den += a * a;
    if (i + 1 < n) num += a * (values[i + 1] - mean);
  }
  if (!(den > 0.0L) || !std::isfinite(static_cast<double>(den))) return kNaN;
  return static_cast<double>(num / den);
}

double lag1_acf_alpha_estimate(std::span<const double> phase, std::size_t m, int d_max) {
  const Lag1Stage stage = lag1_stage(phase, m, d_max);
  if (std::isnan(stage.delta)) return kNaN;
  return 2.0 - 2.0 * (stage.delta + stage.d);
}

double b1_ratio(std::span<const double> phase, std::size_t m) {
  if (m == 0 || phase.empty()) return kNaN;
  const std::size_t n = (phase.size() - 1) / m;  // averages (tau cancels in the ratio)
  if (n < 2) return kNaN;
  // The N-sample variance and the (non-overlapping) Allan variance of the same N m-averages:
  // their positive correlation keeps the ratio steadier than any other denominator would.
  std::vector<double> y(n);
  long double mean = 0.0L;
  for (std::size_t k = 0; k < n; ++k) {
    y[k] = phase[(k + 1) * m] - phase[k * m];
    mean += y[k];
  }
  mean /= static_cast<long double>(n);
  long double variance = 0.0L;
  long double allan = 0.0L;
  for (std::size_t k = 0; k < n; ++k) {
    const long double a = y[k] - mean;
    variance += a * a;
    if (k + 1 < n) {
      const long double diff = static_cast<long double>(y[k + 1]) - y[k];
      allan += diff * diff;
    }
  }
  const long double nm1 = static_cast<long double>(n - 1);
  variance /= nm1;
  allan /= 2.0L * nm1;
  if (!(allan > 0.0L)) return kNaN;
  return static_cast<double>(variance / allan);
}

double b1_expected(std::size_t n_averages, double mu) {
  if (n_averages < 2) return kNaN;
  const double n = static_cast<double>(n_averages);
  if (std::fabs(mu) < 1e-12) return n * std::log(n) / (2.0 * (n - 1.0) * std::log(2.0));
  return n * (1.0 - std::pow(n, mu)) / (2.0 * (n - 1.0) * (1.0 - std::pow(2.0, mu)));
}

double rn_ratio(std::span<const double> phase, std::size_t m) {
  if (m == 0 || phase.size() < 3 * m) return kNaN;
  const std::size_t n = phase.size();
  // Second differences e[k] = x[k+2m] - 2 x[k+m] + x[k], k = 0 .. n-2m-1, computed where
  // needed: this runs at long taus of records of any length, so it must not hold a copy.
  const std::size_t count = n - 2 * m;
  const auto e = [&](std::size_t k) {
    return (phase[k + 2 * m] - phase[k + m]) - (phase[k + m] - phase[k]);
  };
  // Doubles, restarted per block: a ratio that only chooses between two noise types an octave
  // apart does not need long double, but this runs over all of a record of 1e8 samples, so
  // the blocks are spread over the cores (in fixed blocks: the result is thread-independent).
  // Modified part: the mean of e over windows of m consecutive terms (n - 3m + 1 windows), a
  // running sum restarted from a direct sum at every block of max(2^16, m) windows so that
  // rounding cannot build up beyond the statistic's own (percent-level) scatter.
  const std::size_t windows = count - m + 1;
  const std::size_t block = std::max<std::size_t>(std::size_t{1} << 16, m);
  const std::size_t n_blocks = (count + block - 1) / block;
  std::vector<double> allan_parts(n_blocks, 0.0);
  std::vector<double> modified_parts(n_blocks, 0.0);
  const double inv_m2 = 1.0 / (static_cast<double>(m) * static_cast<double>(m));
  detail::parallel_for(n_blocks, 0, [&](std::size_t b) {
    const std::size_t begin = b * block;
    double squares = 0.0;
    for (std::size_t k = begin; k < std::min(count, begin + block); ++k) squares += e(k) * e(k);
    allan_parts[b] = squares;
    const std::size_t w_end = std::min(windows, begin + block);
    if (begin >= w_end) return;
    double window = 0.0;
    for (std::size_t i = begin; i < begin + m; ++i) window += e(i);
    double sum = window * window;
    for (std::size_t j = begin + 1; j < w_end; ++j) {
      // e(j + m - 1) - e(j - 1) as one third difference: four loads instead of six.
      const double* x = phase.data() + (j - 1);
      window += (x[3 * m] - x[0]) - 3.0 * (x[2 * m] - x[m]);
      sum += window * window;
    }
    modified_parts[b] = sum * inv_m2;
  });
  long double allan = 0.0L;
  long double modified = 0.0L;
  for (std::size_t b = 0; b < n_blocks; ++b) {
    allan += allan_parts[b];
    modified += modified_parts[b];
  }
  allan /= static_cast<long double>(count);
  modified /= static_cast<long double>(windows);
  if (!(allan > 0.0L)) return kNaN;
  return static_cast<double>(modified / allan);
}

double rn_expected(int alpha, std::size_t m) {
  if (m == 0 || alpha < -2 || alpha > 2) return kNaN;
  const double F = static_cast<double>(m);
  return detail::power_law_sz(0.0, 1.0, alpha, 2) / detail::power_law_sz(0.0, F, alpha, 2);
}

NoiseId try_identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator) {
  if (m == 0) {
    throw InputError("noise identification: the averaging factor m must be at least 1");
  }
  NoiseId result;
  const int d = family_d(estimator);
  if (d == 0) {
    result.message = "noise identification is not defined for " +
                     std::string(estimator_name(estimator)) + "; force the noise type";
    return result;
  }
  const std::size_t points = decimated_count(phase.size(), m);
  result.points = points;
  const int low = lowest_alpha(d);

  if (points >= kMinLag1AcfPoints) {
    const Lag1Stage stage = lag1_stage(phase, m, d);
    if (std::isnan(stage.delta)) {
      result.message = "noise identification failed at m = " + std::to_string(m) +
                       ": the phase is constant or not finite";
      return result;
    }
    result.statistic = 2.0 - 2.0 * (stage.delta + stage.d);
    result.alpha = classify(stage, m, low);
    result.method = NoiseIdMethod::lag1_acf;
    return result;
  }

  if (points >= kMinB1Averages + 1) {
    const std::size_t averages = points - 1;
    const double b1 = b1_ratio(phase, m);
    if (!(b1 > 0.0) || !std::isfinite(b1)) {
      result.message = "noise identification failed at m = " + std::to_string(m) +
                       ": the phase is constant or not finite";
      return result;
    }
    result.statistic = b1;
    // Nearest expected B1 in the log domain over mu = -2 (PM), -1, 0, 1 (white, flicker,
    // random-walk FM) and, for the Hadamard family, 2 (flicker-walk FM).
    int best_mu = -2;
    double best_distance = std::numeric_limits<double>::infinity();
    const int mu_max = d == 3 ? 2 : 1;
    for (int mu = -2; mu <= mu_max; ++mu) {
      const double distance = std::fabs(std::log(b1 / b1_expected(averages, mu)));
      if (distance < best_distance) {
        best_distance = distance;
        best_mu = mu;
      }
    }
    if (best_mu > -2) {
      result.alpha = -best_mu - 1;
      result.method = NoiseIdMethod::b1_ratio;
      return result;
    }
    // White or flicker PM: R(n) decides (the boundary is the geometric mean).
    const double rn = rn_ratio(phase, m);
    result.method = NoiseIdMethod::b1_rn_ratio;
    result.statistic = rn;
    const double white = rn_expected(2, m);
    const double flicker = rn_expected(1, m);
    result.alpha = (std::isfinite(rn) && m > 1 && rn > std::sqrt(white * flicker)) ? 1 : 2;
    return result;
  }

  result.message = too_few_message(estimator, phase.size(), m);
  return result;
}

NoiseId identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator) {
  NoiseId result = try_identify_noise(phase, m, estimator);
  if (!result.identified()) throw InputError(result.message);
  return result;
}

}  // namespace imunoise
