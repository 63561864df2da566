#include "imunoise/confidence/noise_id.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/error.hpp"
#include "../core/correlation_sums.hpp"
#include "../core/kernels.hpp"   // the deviation engine's vector kernels
#include "../core/parallel.hpp"  // the library's fork-join helper
#include "../core/prefaulted.hpp"
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

// Identification reads at most the first 2^17 decimated points: the lag-1 estimate's
// standard error there is ~1/sqrt(2^17) = 3e-3, ninety times inside the 1/4 decision margin
// (and seventy inside the 0.2 between the nearest model values at m >= 2), and a
// record of 1e8 samples is neither copied nor read in full for every tau.
constexpr std::size_t kMaxIdentificationPoints = std::size_t{1} << 17;

// Lag-1 autocorrelation about the mean of z[0, n) (two passes: mean, then centred sums). Four
// interleaved partial sums per quantity: the loop runs at the load rate instead of waiting on
// one add chain, and the result does not depend on threads or CPU. Doubles suffice: the
// statistic only has to fall on the right side of boundaries ~0.25 apart, and over at most
// 2^17 points its rounding (~1e-13) is ten orders below its own scatter (~3e-3).
double lag1_of(const double* z, std::size_t n) {
  if (n < 3) return kNaN;
  double m0 = 0.0, m1 = 0.0, m2 = 0.0, m3 = 0.0;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    m0 += z[i];
    m1 += z[i + 1];
    m2 += z[i + 2];
    m3 += z[i + 3];
  }
  for (; i < n; ++i) m0 += z[i];
  const double mean = ((m0 + m1) + (m2 + m3)) / static_cast<double>(n);
  double num0 = 0.0, num1 = 0.0, num2 = 0.0, num3 = 0.0;
  double den0 = 0.0, den1 = 0.0, den2 = 0.0, den3 = 0.0;
  i = 0;
  for (; i + 5 <= n; i += 4) {
    const double a0 = z[i] - mean, a1 = z[i + 1] - mean, a2 = z[i + 2] - mean,
                 a3 = z[i + 3] - mean, a4 = z[i + 4] - mean;
    den0 += a0 * a0;
    den1 += a1 * a1;
    den2 += a2 * a2;
    den3 += a3 * a3;
    num0 += a0 * a1;
    num1 += a1 * a2;
    num2 += a2 * a3;
    num3 += a3 * a4;
  }
  for (; i < n; ++i) {
    const double a = z[i] - mean;
    den0 += a * a;
    if (i + 1 < n) num0 += a * (z[i + 1] - mean);
  }
  const double num = (num0 + num1) + (num2 + num3);
  const double den = (den0 + den1) + (den2 + den3);
  if (!(den > 0.0) || !std::isfinite(den)) return kNaN;
  return num / den;
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
  // The decimated phase is gathered once and differenced in place: one strided read of the
  // record per tau (at m >= 8 one cache line per point: the gather is most of the cost), then
  // contiguous passes over at most 1 MB.
  thread_local std::vector<double> z;
  detail::resize_prefaulted(z, points);
  const double* x = phase.data();
  for (std::size_t i = 0; i < points; ++i) z[i] = x[i * m];
  std::size_t n = points;
  for (int d = 0;; ++d) {
    const double r1 = lag1_of(z.data(), n);
    if (std::isnan(r1)) return stage;
    const double delta = r1 / (1.0 + r1);
    if (delta < 0.25 || d >= d_max) {
      stage.delta = delta;
      stage.d = d;
      return stage;
    }
    for (std::size_t i = 0; i + 1 < n; ++i) z[i] = z[i + 1] - z[i];
    --n;
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


}  // namespace

bool noise_identifiable(std::size_t n_phase, std::size_t m) {
  return m > 0 && decimated_count(n_phase, m) >= kMinB1Averages + 1;
}

std::string too_few_for_noise_id(Estimator estimator, std::size_t n_phase, std::size_t m) {
  const std::size_t points = decimated_count(n_phase, m);
  return "too few samples for noise identification (" + std::string(estimator_name(estimator)) +
         " at m = " + std::to_string(m) + "): " + std::to_string(n_phase) + " phase points give " +
         std::to_string(points) + " at stride m; the lag-1 autocorrelation needs " +
         std::to_string(kMinLag1AcfPoints) + " and the B1 ratio " +
         std::to_string(kMinB1Averages + 1) +
         "; use a smaller averaging factor or force the noise type (--noise-type)";
}

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
  // Second differences e[k] = x[k+2m] - 2 x[k+m] + x[k], k = 0 .. n-2m-1, formed where needed
  // by the deviation engine's vector kernels: this runs at long taus of records of any length,
  // so it must not hold a copy. Doubles, in fixed blocks spread over the cores (the result is
  // thread-independent): a ratio that only chooses between two noise types an octave apart
  // does not need long double, but this reads all of a record of 1e8 samples.
  // Modified part: the mean of e over windows of m consecutive terms (n - 3m + 1 windows), a
  // running sum restarted from a direct sum at every block of max(2^16, 4m) windows so that
  // rounding cannot build up beyond the statistic's own (percent-level) scatter (a restart
  // costs m terms: at every m windows they were a sixth of the time at long taus).
  const std::size_t count = n - 2 * m;
  const std::size_t windows = count - m + 1;
  const std::size_t block = std::max<std::size_t>(std::size_t{1} << 16, 4 * m);
  const std::size_t n_blocks = (count + block - 1) / block;
  std::vector<double> allan_parts(n_blocks, 0.0);
  std::vector<double> modified_parts(n_blocks, 0.0);
  const double inv_m2 = 1.0 / (static_cast<double>(m) * static_cast<double>(m));
  const double* x = phase.data();
  // One pass: the window recursion reads e_k for k in [begin, w_end - 1) anyway and returns
  // their squares too; e_{w_end - 1} and the last m - 1 terms past the last window are added
  // directly.
  detail::parallel_for(n_blocks, 0, [&](std::size_t b) {
    const std::size_t begin = b * block;
    const std::size_t w_end = std::min(windows, begin + block);
    if (begin >= w_end) return;
    double squares = 0.0;
    modified_parts[b] =
        detail::sum_sq_window_second_difference(x + begin, m, w_end - begin, &squares) * inv_m2;
    const std::size_t e_end = w_end == windows ? count : w_end;
    allan_parts[b] = squares + detail::sum_sq_second_difference(x + w_end - 1, m, e_end - (w_end - 1));
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

namespace {

// rn_ratio_sampled's stride at m: the largest power of two dividing m that is at most m/64.
std::size_t sampling_stride(std::size_t m) {
  std::size_t q = m & (~m + 1);  // lowest set bit of m
  while (q > m / 64) q /= 2;
  return q;
}

}  // namespace

double rn_ratio_sampled(std::span<const double> phase, std::size_t m, std::size_t min_stride) {
  if (m == 0 || phase.size() < 3 * m) return kNaN;
  const std::size_t q = sampling_stride(m);
  if (q < std::max<std::size_t>(min_stride, 4)) return rn_ratio(phase, m);
  const std::size_t n = phase.size();
  const std::size_t blocks = n / q;  // whole blocks of q samples
  // Prefix sums of the phase at multiples of q: block sums in doubles (fixed blocks, spread
  // over the cores), accumulated in long double, where the window's third difference of the
  // prefix loses nothing to the prefix's size.
  std::vector<double> block_sum(blocks);
  const double* x = phase.data();
  constexpr std::size_t kBlocksPerItem = 16;
  detail::parallel_for((blocks + kBlocksPerItem - 1) / kBlocksPerItem, 0, [&](std::size_t item) {
    const std::size_t end = std::min(blocks, (item + 1) * kBlocksPerItem);
    for (std::size_t b = item * kBlocksPerItem; b < end; ++b) {
      const double* p = x + b * q;
      double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
      for (std::size_t i = 0; i < q; i += 4) {  // q is a power of two >= 4
        s0 += p[i];
        s1 += p[i + 1];
        s2 += p[i + 2];
        s3 += p[i + 3];
      }
      block_sum[b] = (s0 + s1) + (s2 + s3);
    }
  });
  std::vector<long double> prefix(blocks + 1, 0.0L);
  for (std::size_t b = 0; b < blocks; ++b) prefix[b + 1] = prefix[b] + block_sum[b];
  const std::size_t a = m / q;
  // Window at j = k q: v = S(j + 3m) - 3 S(j + 2m) + 3 S(j + m) - S(j), S(t) = sum_{i<t} x_i.
  long double modified = 0.0L;
  std::size_t windows = 0;
  for (std::size_t k = 0; k + 3 * a <= blocks; ++k, ++windows) {
    const long double v = (prefix[k + 3 * a] - prefix[k]) - 3.0L * (prefix[k + 2 * a] - prefix[k + a]);
    modified += v * v;
  }
  // Second differences at the same start points (j + 2m <= n - 1).
  long double allan = 0.0L;
  std::size_t terms = 0;
  for (std::size_t j = 0; j + 2 * m < n; j += q, ++terms) {
    const long double e = (static_cast<long double>(x[j + 2 * m]) - x[j + m]) - (x[j + m] - x[j]);
    allan += e * e;
  }
  if (windows == 0 || terms == 0) return kNaN;
  const long double md = static_cast<long double>(m);
  modified /= md * md * static_cast<long double>(windows);
  allan /= static_cast<long double>(terms);
  if (!(allan > 0.0L)) return kNaN;
  return static_cast<double>(modified / allan);
}

namespace {

// Whether B1 may call for R(n) at m, and rn_ratio_sampled would then read every start.
bool reads_every_start(std::size_t n_phase, std::size_t m) {
  const std::size_t points = decimated_count(n_phase, m);
  return m > 0 && n_phase >= 3 * m && points >= kMinB1Averages + 1 && points < kMinLag1AcfPoints &&
         sampling_stride(m) < 64;
}

// Below this many second differences read in all, rn_ratio at each factor costs less than the
// transforms (1e6 samples: about a second for both sums of every factor on this VM).
constexpr std::size_t kRnBatchTerms = std::size_t{1} << 31;

}  // namespace

std::vector<double> rn_ratios_for_grid(std::span<const double> phase, std::span<const std::size_t> factors,
                                       unsigned threads) {
  const std::size_t n = phase.size();
  std::vector<std::size_t> wanted;
  std::size_t terms = 0;
  for (const std::size_t m : factors) {
    if (!reads_every_start(n, m)) continue;
    wanted.push_back(m);
    terms += n - 2 * m;
  }
  if (terms < kRnBatchTerms) return {};
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  const std::vector<double> by_wanted = rn_ratios(phase, wanted, threads);
  std::vector<double> result(factors.size(), kNaN);
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const auto it = std::lower_bound(wanted.begin(), wanted.end(), factors[t]);
    if (it != wanted.end() && *it == factors[t]) result[t] = by_wanted[static_cast<std::size_t>(it - wanted.begin())];
  }
  return result;
}

std::vector<double> rn_ratios(std::span<const double> phase, std::span<const std::size_t> wanted, unsigned threads) {
  const std::size_t n = phase.size();
  std::vector<double> by_wanted(wanted.size(), kNaN);
  std::vector<std::size_t> valid;  // the factors with 3m <= n (others stay NaN)
  for (const std::size_t m : wanted) {
    if (m > 0 && 3 * m <= n) valid.push_back(m);
  }
  if (valid.size() != wanted.size()) {
    std::vector<double> partial = rn_ratios(phase, valid, threads);
    for (std::size_t t = 0, j = 0; t < wanted.size(); ++t) {
      if (j < valid.size() && wanted[t] == valid[j]) by_wanted[t] = partial[j++];
    }
    return by_wanted;
  }
  // Allan sums from the phase; modified sums are the third differences at lag m of the prefix
  // sums S of the phase (a window of m second differences telescopes to S(j+3m) - 3 S(j+2m) +
  // 3 S(j+m) - S(j)). The prefix is of the phase minus its line (which no window sees), in long
  // double, then rounded: each S value is off by at most eps |S|.
  const detail::CorrelationSums allan = detail::correlation_difference_sums(phase, 2, wanted, threads);
  const std::vector<double> y = detail::detrended_phase(phase, 1);
  std::vector<double> prefix(n + 1, 0.0);
  long double running = 0.0L;
  double prefix_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    running += y[i];
    prefix[i + 1] = static_cast<double>(running);
    prefix_max = std::max(prefix_max, std::abs(prefix[i + 1]));
  }
  const detail::CorrelationSums modified = detail::correlation_difference_sums(
      prefix, 3, wanted, threads, std::numeric_limits<double>::epsilon() * prefix_max);
  constexpr double kRnTolerance = 1e-9;
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    if (!(allan.relative_bound[i] <= kRnTolerance && modified.relative_bound[i] <= kRnTolerance)) continue;
    const double m = static_cast<double>(wanted[i]);
    const double count = static_cast<double>(n - 2 * wanted[i]);
    const double windows = static_cast<double>(n - 3 * wanted[i] + 1);
    by_wanted[i] = (modified.sum_sq[i] / (m * m) / windows) / (allan.sum_sq[i] / count);
  }
  return by_wanted;
}

double rn_expected(int alpha, std::size_t m) {
  if (m == 0 || alpha < -2 || alpha > 2) return kNaN;
  const double F = static_cast<double>(m);
  return detail::power_law_sz(0.0, 1.0, alpha, 2) / detail::power_law_sz(0.0, F, alpha, 2);
}

NoiseId try_identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator) {
  return try_identify_noise(phase, m, estimator, kNaN);
}

NoiseId try_identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator,
                           double known_rn) {
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
    const double rn = std::isnan(known_rn) ? rn_ratio_sampled(phase, m) : known_rn;
    result.method = NoiseIdMethod::b1_rn_ratio;
    result.statistic = rn;
    const double white = rn_expected(2, m);
    const double flicker = rn_expected(1, m);
    result.alpha = (std::isfinite(rn) && m > 1 && rn > std::sqrt(white * flicker)) ? 1 : 2;
    return result;
  }

  result.message = too_few_for_noise_id(estimator, phase.size(), m);
  return result;
}

NoiseId identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator) {
  NoiseId result = try_identify_noise(phase, m, estimator);
  if (!result.identified()) throw InputError(result.message);
  return result;
}

}  // namespace imunoise
