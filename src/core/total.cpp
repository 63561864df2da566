#include "imunoise/total.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <vector>

#include "domain_check.hpp"
#include "imunoise/hadamard.hpp"
#include "parallel.hpp"
#include "square_sum.hpp"

namespace imunoise {
namespace {

// The inverted-reflection extension of totvar: ext[j + N - 2] = x*[j], j = -(N-2) .. 2N-3.
std::vector<double> reflect_inverted(std::span<const double> x) {
  const std::size_t n = x.size();
  const std::size_t pad = n - 2;
  std::vector<double> ext(n + 2 * pad);
  for (std::size_t j = 1; j <= pad; ++j) ext[pad - j] = 2.0 * x[0] - x[j];
  for (std::size_t i = 0; i < n; ++i) ext[pad + i] = x[i];
  for (std::size_t j = 1; j <= pad; ++j) ext[pad + n - 1 + j] = 2.0 * x[n - 1] - x[n - 1 - j];
  return ext;
}

// sum_{i=begin}^{end-1} f(i) in four interleaved partial sums (fixed order).
template <class F>
double sum4(std::size_t begin, std::size_t end, F&& f) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) {
    s0 += f(i);
    s1 += f(i + 1);
    s2 += f(i + 2);
    s3 += f(i + 3);
  }
  for (; i < end; ++i) s0 += f(i);
  return (s0 + s1) + (s2 + s3);
}

// The shared mtot/htot kernel over a sequence u of length L: returns
//   sum_{n=0}^{L-3m} (1/(6m)) sum_{j=0}^{6m-1} z_j(n)^2
// (see total.hpp). O(m) per subsequence with the odd-extension prefix trick.
class ReflectedKernel {
 public:
  explicit ReflectedKernel(std::size_t m) : m_(m), p_(3 * m + 1), pe_(9 * m + 1) {}

  // Mtot(n) for the subsequence u[0..3m-1].
  double subsequence(const double* u) {
    const std::size_t m = m_;
    const std::size_t len = 3 * m;
    const std::size_t h = len / 2;
    // Half-average slope of the points relative to the first one. Sums in four interleaved
    // chains (and the prefix below in four quarters) so that no long dependent chain of
    // additions sets the pace: this kernel runs (N - 3m + 1) times per factor.
    const double u0 = u[0];
    const double first = sum4(0, h, [&](std::size_t i) { return u[i] - u0; });
    const double second = sum4(len - h, len, [&](std::size_t i) { return u[i] - u0; });
    const double slope = (second - first) / (static_cast<double>(h) * static_cast<double>(len - h));
    auto detrended = [&](std::size_t i) { return (u[i] - u0) - slope * static_cast<double>(i); };
    // Detrended points about their mean keep the prefix sums small.
    const double mean = sum4(0, len, detrended) / static_cast<double>(len);
    const std::size_t quarter = (len + 3) / 4;
    const std::size_t last = len - 3 * quarter <= quarter ? len - 3 * quarter : 0;  // length of the 4th quarter
    double run0 = 0.0, run1 = 0.0, run2 = 0.0, run3 = 0.0;
    p_[0] = 0.0;
    for (std::size_t t = 0; t < quarter; ++t) {
      run0 += detrended(t) - mean;
      p_[t + 1] = run0;
      if (quarter + t < len) {
        run1 += detrended(quarter + t) - mean;
        p_[quarter + t + 1] = run1;
      }
      if (2 * quarter + t < len) {
        run2 += detrended(2 * quarter + t) - mean;
        p_[2 * quarter + t + 1] = run2;
      }
      if (t < last) {
        run3 += detrended(3 * quarter + t) - mean;
        p_[3 * quarter + t + 1] = run3;
      }
    }
    const double offsets[3] = {run0, run0 + run1, run0 + run1 + run2};
    for (std::size_t c = 1; c < 4; ++c) {
      const std::size_t begin = std::min(len, c * quarter);
      const std::size_t end = std::min(len, (c + 1) * quarter);
      const double offset = offsets[c - 1];
      for (std::size_t i = begin; i < end; ++i) p_[i + 1] += offset;
    }
    const double total = p_[len];
    // Prefix of the 9m reflected sequence [reverse(y), y, reverse(y)], less the constant T
    // (third differences cancel it): odd extensions of P about the folds at 3m and 6m.
    for (std::size_t q = 0; q <= len; ++q) pe_[q] = -p_[len - q];
    for (std::size_t q = len; q <= 2 * len; ++q) pe_[q] = p_[q - len];
    for (std::size_t q = 2 * len; q <= 3 * len; ++q) pe_[q] = 2.0 * total - p_[3 * len - q];
    const double* pe = pe_.data();
    const double sum = detail::square_sum4(6 * m, [&](std::size_t j) {
      return (pe[j + 3 * m] - pe[j]) - 3.0 * (pe[j + 2 * m] - pe[j + m]);
    });
    const double md = static_cast<double>(m);
    return sum / (md * md * 6.0 * md);
  }

 private:
  std::size_t m_;
  std::vector<double> p_;
  std::vector<double> pe_;
};

// sum_n Mtot(n) over every 3m-point subsequence of u, the subsequences split over threads in
// fixed blocks (the result does not depend on the thread count).
long double reflected_sum(std::span<const double> u, std::size_t m, unsigned threads) {
  const std::size_t count = u.size() - 3 * m + 1;
  constexpr std::size_t kBlock = 256;
  const std::size_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<long double> partial(blocks, 0.0L);
  const unsigned workers = (count * m < 200000) ? 1 : threads;
  // One kernel per block keeps the scratch local; its allocation is O(m), small next to O(m) per
  // subsequence times the block size.
  detail::parallel_for(blocks, workers, [&](std::size_t b) {
    ReflectedKernel kernel(m);
    const std::size_t end = std::min(count, (b + 1) * kBlock);
    long double sum = 0.0L;
    for (std::size_t n = b * kBlock; n < end; ++n) sum += kernel.subsequence(u.data() + n);
    partial[b] = sum;
  });
  long double total = 0.0L;
  for (const long double p : partial) total += p;
  return total;
}

}  // namespace

std::vector<DevPoint> totdev(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::totdev, phase, tau0_s, factors);
  std::vector<DevPoint> points(factors.size());
  if (factors.empty()) return points;
  const std::vector<double> ext = reflect_inverted(phase);
  const std::size_t n = phase.size();
  const std::size_t pad = n - 2;
  detail::parallel_for(factors.size(), options.threads, [&](std::size_t t) {
    const std::size_t m = factors[t];
    const double* c = ext.data() + pad;  // c[i] = x*[i]
    // Interior points i = 1 .. N-2 of the reflected sequence.
    const long double sum = detail::square_sum4(n - 2, [&](std::size_t j) {
      const std::size_t i = j + 1;
      return (c[i + m] - c[i]) - (c[i] - c[i - m]);
    });
    const double tau_s = static_cast<double>(m) * tau0_s;
    points[t].m = m;
    points[t].tau_s = tau_s;
    points[t].n = n - 2;
    points[t].dev =
        std::sqrt(static_cast<double>(sum / (2.0L * static_cast<long double>(n - 2)))) / tau_s;
  });
  return points;
}

std::vector<DevPoint> mtotdev(std::span<const double> phase, double tau0_s,
                              std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::mtotdev, phase, tau0_s, factors);
  std::vector<DevPoint> points(factors.size());
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const std::size_t m = factors[t];
    const std::size_t count = phase.size() - 3 * m + 1;
    const long double sum = reflected_sum(phase, m, options.threads);
    const double tau_s = static_cast<double>(m) * tau0_s;
    points[t].m = m;
    points[t].tau_s = tau_s;
    points[t].n = count;
    points[t].dev = std::sqrt(static_cast<double>(sum / (2.0L * count))) / tau_s;
  }
  return points;
}

std::vector<DevPoint> ttotdev(std::span<const double> phase, double tau0_s,
                              std::span<const std::size_t> factors, const DevOptions& options) {
  auto points = mtotdev(phase, tau0_s, factors, options);
  for (auto& point : points) point.dev *= point.tau_s / std::sqrt(3.0);
  return points;
}

std::vector<DevPoint> htotdev(std::span<const double> phase, double tau0_s,
                              std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::htotdev, phase, tau0_s, factors);
  std::vector<DevPoint> points(factors.size());
  if (factors.empty()) return points;
  std::vector<double> rate(phase.size() - 1);
  for (std::size_t k = 0; k + 1 < phase.size(); ++k) rate[k] = (phase[k + 1] - phase[k]) / tau0_s;
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const std::size_t m = factors[t];
    if (m == 1) {  // Stable32: the overlapping Hadamard deviation at m = 1
      const std::size_t one[1] = {1};
      points[t] = ohdev(phase, tau0_s, one, options).front();
      continue;
    }
    const std::size_t count = rate.size() - 3 * m + 1;
    const long double sum = reflected_sum(rate, m, options.threads);
    points[t].m = m;
    points[t].tau_s = static_cast<double>(m) * tau0_s;
    points[t].n = count;
    points[t].dev = std::sqrt(static_cast<double>(sum / (6.0L * count)));
  }
  return points;
}

double bias_variance_factor(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (m == 0 || n_phase == 0) return kNaN;
  const double mm = static_cast<double>(m);
  switch (estimator) {
    case Estimator::totdev: {
      if (alpha == 2 || alpha == 1 || alpha == 0) return 1.0;
      const double a = alpha == -1 ? 1.0 / (3.0 * std::log(2.0)) : alpha == -2 ? 0.75 : kNaN;
      const double b = 1.0 - a * mm / static_cast<double>(n_phase);
      return b > 0.0 ? 1.0 / b : kNaN;
    }
    case Estimator::mtotdev:
    case Estimator::ttotdev: {
      constexpr std::array<double, 5> kRatio{0.94, 0.83, 0.73, 0.70, 0.69};
      if (alpha < -2 || alpha > 2) return kNaN;
      return 1.0 / kRatio[static_cast<std::size_t>(2 - alpha)];
    }
    case Estimator::htotdev: {
      constexpr std::array<double, 5> kA{-0.005, -0.149, -0.229, -0.283, -0.321};
      if (m == 1 || alpha > 0 || alpha < -4) return kNaN;
      return 1.0 / (1.0 + kA[static_cast<std::size_t>(-alpha)]);
    }
    case Estimator::theo1: {
      struct Abc {
        double a, b, c;
      };
      constexpr std::array<Abc, 5> kTheo{
          {{0.09, 0.74, 0.40}, {0.14, 0.82, 0.30}, {1.0, 0.0, 0.0}, {1.87, -1.05, 0.79},
           {2.70, -1.53, 0.85}}};
      if (alpha < -2 || alpha > 2) return kNaN;
      const Abc t = kTheo[static_cast<std::size_t>(2 - alpha)];
      return t.a + t.b / std::pow(0.75 * mm, t.c);
    }
    default:
      return kNaN;
  }
}

std::size_t apply_bias_correction(std::vector<DevPoint>& points, Estimator estimator,
                                  std::size_t n_phase) {
  std::size_t corrected = 0;
  for (auto& p : points) {
    if (p.alpha == std::numeric_limits<int>::min()) continue;
    const double factor = bias_variance_factor(estimator, p.alpha, p.m, n_phase);
    if (!(factor > 0.0) || !std::isfinite(factor)) continue;
    const double scale = std::sqrt(factor);
    p.dev *= scale;
    p.ci_low *= scale;
    p.ci_high *= scale;
    ++corrected;
  }
  return corrected;
}

}  // namespace imunoise
