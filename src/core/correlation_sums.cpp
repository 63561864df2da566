#include "correlation_sums.hpp"

#include <fftw3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "parallel.hpp"

namespace imunoise::detail {
namespace {

// FFTW's planner is not thread-safe; executing a plan on new arrays of the same alignment is.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
using RealBuffer = std::unique_ptr<double[], FftwFree>;
using ComplexBuffer = std::unique_ptr<fftw_complex[], FftwFree>;

RealBuffer real_buffer(std::size_t n) { return RealBuffer(fftw_alloc_real(n)); }
ComplexBuffer complex_buffer(std::size_t n) { return ComplexBuffer(fftw_alloc_complex(n)); }

std::size_t power_of_two_at_least(std::size_t n) {
  std::size_t L = 1;
  while (L < n) L *= 2;
  return L;
}

// Forward and inverse real plans per transform length, made once (FFTW_ESTIMATE: no trial
// runs, so the same plan, and the same rounding, on every machine run) and shared by threads.
class Plans {
 public:
  struct Pair {
    fftw_plan forward = nullptr, inverse = nullptr;
  };
  const Pair& of(std::size_t L) {
    const std::lock_guard lock(planner_mutex());
    auto [it, fresh] = plans_.try_emplace(L);
    if (fresh) {
      RealBuffer real = real_buffer(L);
      ComplexBuffer spectrum = complex_buffer(L / 2 + 1);
      const int n = static_cast<int>(L);
      it->second.forward = fftw_plan_dft_r2c_1d(n, real.get(), spectrum.get(), FFTW_ESTIMATE);
      it->second.inverse = fftw_plan_dft_c2r_1d(n, spectrum.get(), real.get(), FFTW_ESTIMATE);
    }
    return it->second;
  }
  Plans() = default;
  Plans(const Plans&) = delete;
  Plans& operator=(const Plans&) = delete;
  ~Plans() {
    const std::lock_guard lock(planner_mutex());
    for (auto& [L, pair] : plans_) {
      fftw_destroy_plan(pair.forward);
      fftw_destroy_plan(pair.inverse);
    }
  }

 private:
  std::map<std::size_t, Pair> plans_;
};

// c[l] = sum_{p < nu} u[p] w[p + l] for l = 0, step, 2 step, ... < n_lags, added to
// out[l / step]; w is read in [0, min(nu + n_lags - 1, w_size)), zero past w_size.
void add_correlation(const double* u, std::size_t nu, const double* w, std::size_t w_size, std::size_t n_lags,
                     std::size_t step, Plans& plans, double* out) {
  const std::size_t nw = nu + n_lags - 1;
  const std::size_t L = power_of_two_at_least(nw);  // no wrap: p + l <= nw - 1 < L
  const Plans::Pair& plan = plans.of(L);
  RealBuffer a = real_buffer(L), b = real_buffer(L);
  ComplexBuffer fa = complex_buffer(L / 2 + 1), fb = complex_buffer(L / 2 + 1);
  std::copy_n(u, nu, a.get());
  std::fill(a.get() + nu, a.get() + L, 0.0);
  const std::size_t nb = std::min(nw, w_size);
  std::copy_n(w, nb, b.get());
  std::fill(b.get() + nb, b.get() + L, 0.0);
  fftw_execute_dft_r2c(plan.forward, a.get(), fa.get());
  fftw_execute_dft_r2c(plan.forward, b.get(), fb.get());
  for (std::size_t k = 0; k <= L / 2; ++k) {
    // conj(A) * B: the correlation sum_p u[p] w[p + l]
    const double re = fa[k][0] * fb[k][0] + fa[k][1] * fb[k][1];
    const double im = fa[k][0] * fb[k][1] - fa[k][1] * fb[k][0];
    fb[k][0] = re;
    fb[k][1] = im;
  }
  fftw_execute_dft_c2r(plan.inverse, fb.get(), a.get());
  const double scale = 1.0 / static_cast<double>(L);
  for (std::size_t l = 0, j = 0; l < n_lags; l += step, ++j) out[j] += a[l] * scale;
}

// Below this many factors a wedge is summed directly (n^2 alpha / 2 products).
constexpr std::size_t kDirectWedge = 512;

// out[m] += sum_{p < alpha m} u[p] v[p + beta m] for m in [0, n). The factors split in halves:
// the lower half is the same wedge on [0, h); for the upper half every p < alpha h is inside
// (one correlation at lags beta m), and the rest, p in [alpha h, alpha m), is again a wedge
// on u + alpha h and v + (alpha + beta) h over m - h in [0, n - h).
void add_wedge(const double* u, const double* v, std::size_t n, std::size_t alpha, std::size_t beta,
               Plans& plans, double* out) {
  if (n <= kDirectWedge) {
    for (std::size_t m = 1; m < n; ++m) {
      double sum = 0.0;
      const double* vm = v + beta * m;
      for (std::size_t p = 0; p < alpha * m; ++p) sum += u[p] * vm[p];
      out[m] += sum;
    }
    return;
  }
  const std::size_t h = n / 2;
  add_wedge(u, v, h, alpha, beta, plans, out);
  const std::size_t lags = beta * (n - h - 1) + 1;
  add_correlation(u, alpha * h, v + beta * h, alpha * h + lags - 1, lags, beta, plans, out + h);
  add_wedge(u + alpha * h, v + (alpha + beta) * h, n - h, alpha, beta, plans, out + h);
}

struct Pair {
  std::size_t a, b;
};

}  // namespace

// Differences of order K cannot see a polynomial of degree < K, and without it the
// correlations (and their rounding) would grow with the phase's mean, drift and curvature.
// Least squares on polynomials orthogonal over the symmetric grid t = i - (n - 1)/2: 1, t and
// t^2 - mean(t^2), so each coefficient is one ratio of sums.
std::vector<double> detrended_phase(std::span<const double> x, int degree) {
  const std::size_t n = x.size();
  const long double centre = static_cast<long double>(n - 1) / 2.0L;
  long double t2_mean = 0.0L;
  for (std::size_t i = 0; i < n; ++i) {
    const long double t = static_cast<long double>(i) - centre;
    t2_mean += t * t;
  }
  t2_mean /= static_cast<long double>(std::max<std::size_t>(n, 1));
  std::array<long double, 3> dot{}, norm{}, coefficient{};
  auto basis = [&](std::size_t i, int k) -> long double {
    const long double t = static_cast<long double>(i) - centre;
    return k == 0 ? 1.0L : k == 1 ? t : t * t - t2_mean;
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k <= degree; ++k) {
      const long double b = basis(i, k);
      dot[k] += b * x[i];
      norm[k] += b * b;
    }
  }
  for (int k = 0; k <= degree; ++k) coefficient[k] = norm[k] > 0.0L ? dot[k] / norm[k] : 0.0L;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    long double fit = 0.0L;
    for (int k = 0; k <= degree; ++k) fit += coefficient[k] * basis(i, k);
    y[i] = static_cast<double>(static_cast<long double>(x[i]) - fit);
  }
  return y;
}

CorrelationSums correlation_difference_sums(std::span<const double> phase, int order,
                                            std::span<const std::size_t> factors, unsigned threads,
                                            double input_rounding) {
  const std::size_t n_factors = factors.size();
  CorrelationSums result{std::vector<double>(n_factors, 0.0),
                         std::vector<double>(n_factors, std::numeric_limits<double>::infinity())};
  const std::size_t n = phase.size();
  const std::size_t K = static_cast<std::size_t>(order);
  std::size_t top = 0;
  for (const std::size_t m : factors) {
    if (K * m < n) top = std::max(top, m);
  }
  if (top == 0) return result;

  const std::vector<double> y = detrended_phase(phase, std::min(order - 1, 2));
  std::vector<double> reversed(y.rbegin(), y.rend());
  // Prefix sums of y^2 (long double: their differences are the squares' part of every sum).
  std::vector<long double> energy(n + 1, 0.0L);
  for (std::size_t i = 0; i < n; ++i) energy[i + 1] = energy[i] + static_cast<long double>(y[i]) * y[i];

  const std::array<double, 4> c = order == 2 ? std::array<double, 4>{1.0, -2.0, 1.0, 0.0}
                                             : std::array<double, 4>{-1.0, 3.0, -3.0, 1.0};
  std::vector<Pair> pairs;
  for (std::size_t a = 0; a <= K; ++a) {
    for (std::size_t b = a + 1; b <= K; ++b) pairs.push_back({a, b});
  }
  // Jobs: the autocorrelation, then for each pair its head wedge (alpha = a) on y and its
  // tail wedge (alpha = K - b) on y reversed, both at beta = b - a, each into its own array.
  const std::size_t M = top + 1;
  Plans plans;
  std::vector<double> autocorrelation(K * top + 1, 0.0);
  std::vector<std::vector<double>> heads(pairs.size()), tails(pairs.size());
  struct Job {
    const double* series;
    std::size_t alpha, beta;
    std::vector<double>* out;
  };
  std::vector<Job> jobs;
  for (std::size_t j = 0; j < pairs.size(); ++j) {
    const auto [a, b] = pairs[j];
    if (a > 0) jobs.push_back({y.data(), a, b - a, &heads[j]});
    if (K - b > 0) jobs.push_back({reversed.data(), K - b, b - a, &tails[j]});
  }
  // The autocorrelation (the largest transform) first, so the wedges fill the other core.
  parallel_for(jobs.size() + 1, threads, [&](std::size_t item) {
    if (item == 0) {
      add_correlation(y.data(), n, y.data(), n, K * top + 1, 1, plans, autocorrelation.data());
      return;
    }
    const Job& job = jobs[item - 1];
    job.out->assign(M, 0.0);
    add_wedge(job.series, job.series, M, job.alpha, job.beta, plans, job.out->data());
  });

  const double epsilon = std::numeric_limits<double>::epsilon();
  double weight = 0.0;
  for (std::size_t a = 0; a <= K; ++a) weight += std::abs(c[a]);
  const double bound = kCorrelationRounding * epsilon * weight * weight * static_cast<double>(energy[n]);
  // Each difference d also moves by up to weight * (rounding of one value): |sum 2 d dd| is at
  // most 2 sqrt(count * sum) * weight * (input_rounding + the detrending's eps |y|).
  double y_max = 0.0;
  for (const double v : y) y_max = std::max(y_max, std::abs(v));
  const double per_value = 2.0 * weight * (input_rounding + epsilon * y_max);
  for (std::size_t t = 0; t < n_factors; ++t) {
    const std::size_t m = factors[t];
    if (m == 0 || K * m >= n) continue;
    const std::size_t count = n - K * m;
    long double sum = 0.0L;
    for (std::size_t a = 0; a <= K; ++a) {
      sum += static_cast<long double>(c[a] * c[a]) * (energy[a * m + count] - energy[a * m]);
    }
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      const auto [a, b] = pairs[j];
      long double restricted = autocorrelation[(b - a) * m];
      if (a > 0) restricted -= heads[j][m];
      if (K - b > 0) restricted -= tails[j][m];
      sum += 2.0L * c[a] * c[b] * restricted;
    }
    const double total = static_cast<double>(sum);
    result.sum_sq[t] = total;
    if (total > 0.0) {
      result.relative_bound[t] = (bound + per_value * std::sqrt(static_cast<double>(count) * total)) / total;
    }
  }
  return result;
}

}  // namespace imunoise::detail
