#include "imunoise/total.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <vector>

#include "domain_check.hpp"
#include "imunoise/hadamard.hpp"
#include "kernels.hpp"
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

// Prefix sums ul[i] = sum_{k<i} v[k] of v[k] = (u[first+k] - u[first]) - s k, the block's own
// offset and end-to-end slope s removed so that the sums stay at the size of the local
// excursions (a large rate offset would otherwise cost digits); zero past the end of u.
std::vector<double> local_prefix(std::span<const double> u, std::size_t first,
                                 std::size_t size) {
  const std::size_t valid = std::min(size - 1, u.size() - first);
  const double base = u[first];
  const double slope =
      valid > 1 ? (u[first + valid - 1] - base) / static_cast<double>(valid - 1) : 0.0;
  std::vector<double> ul(size);
  double run = 0.0;
  ul[0] = 0.0;
  for (std::size_t k = 0; k + 1 < size; ++k) {
    if (k < valid) run += (u[first + k] - base) - slope * static_cast<double>(k);
    ul[k + 1] = run;
  }
  return ul;
}

// sum_n Mtot(n) over every 3m-point subsequence of u. Blocks of subsequences (the size depends
// on m only) go to the threads, each with its own local prefix, so the result does not depend
// on the thread count; the block spans about twice the subsequence length at most, which
// bounds the size of the prefix sums.
long double reflected_sum(std::span<const double> u, std::size_t m, unsigned threads) {
  const std::size_t count = u.size() - 3 * m + 1;
  const std::size_t block = std::min<std::size_t>(512, (std::max<std::size_t>(3 * m, 8) + 7) / 8 * 8);
  const std::size_t blocks = (count + block - 1) / block;
  std::vector<long double> partial(blocks, 0.0L);
  const unsigned workers = (count * m < 200000) ? 1 : threads;
  detail::parallel_for(blocks, workers, [&](std::size_t b) {
    const std::size_t first = b * block;
    const std::size_t windows = std::min(count - first, block);
    const auto ul = local_prefix(u, first, windows + 3 * m + 8);
    partial[b] = detail::reflected_window_sum(ul.data(), m, windows);
  });
  long double total = 0.0L;
  for (const long double p : partial) total += p;
  return total;
}

}  // namespace

std::vector<DevPoint> totdev(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::totdev, phase, tau0_s, factors);
  return totdev_reflected_range(phase, tau0_s, factors, options);
}

std::vector<DevPoint> totdev_reflected_range(std::span<const double> phase, double tau0_s,
                                             std::span<const std::size_t> factors,
                                             const DevOptions& options) {
  // The N-2 reflected points on each side reach i - m and i + m for every i = 1..N-2 as long
  // as m <= N-1; only the rate check of check_factors is repeated here.
  detail::check_factors(Estimator::totdev, phase, tau0_s, {});
  for (const std::size_t m : factors) {
    if (phase.size() < 3 || m == 0 || m > phase.size() - 1) {
      throw InputError("totdev: averaging factor m = " + std::to_string(m) +
                       " is outside the reflected range 1..N-1 for " +
                       std::to_string(phase.size()) + " phase samples (N >= 3)");
    }
  }
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
