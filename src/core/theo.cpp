#include "imunoise/theo.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "domain_check.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "parallel.hpp"
#include "square_sum.hpp"

namespace imunoise {
namespace {

// Adds, for every span d in [d0, d1), sum_{i=0}^{count-1} (x[i] - x[i+k-d] + x[i+m] - x[i+k+d])^2
// to acc[d - d0]. The i range is cut into blocks of kBlock points and all spans of a block are
// done before the next block: x[i..] and x[i+m..] stay in L1 across spans and the two sliding
// streams move by one point per span, so the pass runs from L1 instead of streaming the whole
// record from memory once per span (4x faster at 1e5 points). The order of the additions per
// span is fixed (blocks in order, four partial sums inside), so results never depend on threads.
constexpr std::size_t kBlock = 512;

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void span_sums(const double* x, std::size_t count, std::size_t k, std::size_t m, std::size_t d0,
               std::size_t d1, double* acc) {
  for (std::size_t i0 = 0; i0 < count; i0 += kBlock) {
    const std::size_t len = std::min(kBlock, count - i0);
    const double* xi = x + i0;
    const double* xm = xi + m;
    for (std::size_t d = d0; d < d1; ++d) {
      const double* xa = xi + (k - d);
      const double* xb = xi + (k + d);
      acc[d - d0] += detail::square_sum4(
          len, [&](std::size_t i) { return (xi[i] - xa[i]) + (xm[i] - xb[i]); });
    }
  }
}

}  // namespace

std::vector<DevPoint> theo1(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options) {
  detail::check_factors(Estimator::theo1, phase, tau0_s, factors);
  std::vector<DevPoint> points(factors.size());
  const std::size_t n = phase.size();
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const std::size_t m = factors[t];
    const std::size_t k = m / 2;
    const std::size_t count = n - m;
    std::vector<double> by_span(k, 0.0);
    // Spans in chunks of 64 over the threads (each chunk owns its slots of by_span).
    constexpr std::size_t kChunk = 64;
    const std::size_t chunks = (k + kChunk - 1) / kChunk;
    // A second thread pays off only for about a millisecond of work: starting and joining one
    // cost ~0.5 ms on the 2026-12-05 VM (its stack and TLS fault in at ~26 us a page), and
    // span_sums does ~3 terms a nanosecond (theo1 on 2,000 samples: 2 threads 7.1-8.0 ms
    // whole process, 1 thread 6.4-6.6 ms).
    const unsigned workers = count * k < 4'000'000 ? 1 : options.threads;
    detail::parallel_for(chunks, workers, [&](std::size_t c) {
      const std::size_t d0 = c * kChunk;
      const std::size_t d1 = std::min(k, d0 + kChunk);
      span_sums(phase.data(), count, k, m, d0, d1, by_span.data() + d0);
    });
    for (std::size_t d = 0; d < k; ++d) by_span[d] /= static_cast<double>(k - d);
    long double sum = 0.0L;
    for (const double s : by_span) sum += s;
    const double mt = static_cast<double>(m) * tau0_s;
    points[t].m = m;
    points[t].tau_s = 0.75 * mt;
    points[t].n = count * k;
    points[t].dev = std::sqrt(static_cast<double>(sum / (0.75L * count)) / (mt * mt));
  }
  return points;
}

std::size_t theobr_ratio_count(std::size_t n_phase, TheoBrRatios ratios) {
  const std::size_t divisor = ratios == TheoBrRatios::stable32 ? 6 : 30;
  if (n_phase < 90 || n_phase / divisor < 3) return 0;
  const std::size_t n = n_phase / divisor - 3;
  const std::size_t avar_max = (n_phase - 1) / 2;
  std::size_t count = 0;
  for (std::size_t i = 0; i <= n && 9 + 3 * i <= avar_max; ++i) ++count;
  return count;
}

TheoBrRatios parse_theobr_ratios(std::string_view name) {
  if (name == "taylor-howe") return TheoBrRatios::taylor_howe;
  if (name == "stable32") return TheoBrRatios::stable32;
  throw InputError("unknown ThêoBR ratio rule '" + std::string(name) +
                   "'; known: taylor-howe (n = N/30 - 3), stable32 (n = N/6 - 3)");
}

TheoBiasFactor theobr_bias_factor(std::span<const double> phase, double tau0_s,
                                  const DevOptions& options, TheoBrRatios rule) {
  const std::size_t ratios = theobr_ratio_count(phase.size(), rule);
  if (ratios == 0) {
    throw InputError("theobr: its bias factor needs at least 90 phase samples, got " +
                     std::to_string(phase.size()) + "; use theo1 (no bias removal) instead");
  }
  std::vector<std::size_t> avar_factors(ratios);
  std::vector<std::size_t> theo_factors(ratios);
  for (std::size_t i = 0; i < ratios; ++i) {
    avar_factors[i] = 9 + 3 * i;
    theo_factors[i] = 12 + 4 * i;
  }
  const auto avar = oadev(phase, tau0_s, avar_factors, options);
  const auto theo = theo1(phase, tau0_s, theo_factors, options);
  long double sum = 0.0L;
  for (std::size_t i = 0; i < ratios; ++i) {
    const double ratio = avar[i].dev / theo[i].dev;
    sum += static_cast<long double>(ratio) * ratio;
  }
  const double kf = static_cast<double>(sum / static_cast<long double>(ratios));
  if (!std::isfinite(kf) || !(kf > 0.0)) {
    throw InputError("theobr: the bias factor Avar/Theo1 is not a positive number (constant data?)");
  }
  return {kf, ratios};
}

std::vector<DevPoint> theobr(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options,
                             TheoBrRatios ratios, TheoBiasFactor* bias_factor) {
  detail::check_factors(Estimator::theobr, phase, tau0_s, factors);
  const TheoBiasFactor kf = theobr_bias_factor(phase, tau0_s, options, ratios);
  auto points = theo1(phase, tau0_s, factors, options);
  const double scale = std::sqrt(kf.avar_over_theo1);
  for (auto& point : points) point.dev *= scale;
  if (bias_factor != nullptr) *bias_factor = kf;
  return points;
}

double theobr_bias_factor_terms(std::size_t n_phase, TheoBrRatios rule) {
  const std::size_t ratios = theobr_ratio_count(n_phase, rule);
  double terms = 0.0;
  for (std::size_t i = 0; i < ratios; ++i) {
    const double m = static_cast<double>(12 + 4 * i);
    terms += (static_cast<double>(n_phase) - m) * 0.5 * m;
  }
  return terms;
}

std::vector<std::size_t> estimator_averaging_factors(Estimator estimator, const TauGrid& grid,
                                                     double rate_hz, std::size_t n_phase) {
  const std::size_t max_m = max_averaging_factor(estimator, n_phase);
  if (!requires_even_factor(estimator)) return averaging_factors(grid, rate_hz, max_m);
  const std::string name(estimator_name(estimator));
  std::set<std::size_t> out;
  switch (grid.kind) {
    case TauGrid::Kind::octave:
      for (std::size_t m = 2; m <= max_m; m *= 2) out.insert(m);
      break;
    case TauGrid::Kind::decade:
      for (std::size_t decade = 1; decade <= max_m; decade *= 10) {
        for (const std::size_t step : {1, 2, 4}) {
          const std::size_t m = step * decade;
          if (m % 2 == 0 && m <= max_m) out.insert(m);
        }
      }
      break;
    case TauGrid::Kind::all:
      for (std::size_t m = 2; m <= max_m; m += 2) out.insert(m);
      break;
    case TauGrid::Kind::per_decade:
      for (int i = 0;; ++i) {
        const double v = std::pow(10.0, static_cast<double>(i) / grid.per_decade);
        const auto m = static_cast<std::size_t>(std::max(1.0, std::round(v / 2.0))) * 2;
        if (m > max_m) break;
        out.insert(m);
      }
      break;
    case TauGrid::Kind::factors:
      for (const std::size_t m : grid.factors) {
        if (m == 0 || m % 2 != 0 || m > max_m) {
          throw InputError(name + ": averaging factor " + std::to_string(m) +
                           " must be even and in 2.." + std::to_string(max_m));
        }
        out.insert(m);
      }
      break;
    case TauGrid::Kind::taus_s:
      for (const double tau_s : grid.taus_s) {
        const double exact = tau_s * rate_hz / 0.75;
        const double m = std::round(exact);
        if (!(m >= 2.0) || std::fabs(exact - m) > 1e-6 * m || static_cast<std::size_t>(m) % 2 != 0 ||
            m > static_cast<double>(max_m)) {
          throw InputError(name + ": tau = " + fmt::format("{:g}", tau_s) +
                           " s is not 0.75 m / rate for an even m in 2.." + std::to_string(max_m) +
                           " (" + name + " taus are 1.5, 3, 4.5, ... sample intervals)");
        }
        out.insert(static_cast<std::size_t>(m));
      }
      break;
  }
  return {out.begin(), out.end()};
}

}  // namespace imunoise
