// Covariance of overlapping Allan variance estimates at several taus under a noise model.
//
// Derivation. Let a_k = x[k+2m] - 2 x[k+m] + x[k] (k = 0..n_i-1, n_i = N - 2 m_i) and b_l the
// same at m_j. The estimate is s_i = sum_k a_k^2 / (2 tau_i^2 n_i). For a zero-mean Gaussian
// process Isserlis' theorem gives Cov(a^2, b^2) = 2 Cov(a, b)^2, so
//   Cov(s_i, s_j) = 2 sum_k sum_l Cov(a_k, b_l)^2 / (4 tau_i^2 tau_j^2 n_i n_j).
// Cov(a_k, b_l) depends on delta = k - l only: f(delta) = sum_pq c_p c_q C(tau0 (delta + p m_i -
// q m_j)), c = (1, -2, 1), with C the generalised covariance of the phase (valid for second
// differences, whose coefficients annihilate polynomials of degree < 2):
//   white rate noise N^2:   C(t) = -N^2 |t| / 2       (Brownian phase)
//   rate random walk K^2:   C(t) =  K^2 |t|^3 / 12    (integrated Brownian phase)
//   flicker rate noise B^2: C(t) =  B^2 t^2 ln|t| / (2 pi)
//   white angle noise Q^2:  C(0) =  Q^2, else 0.
//   Gauss-Markov rate sigma^2, correlation time T (optional, one T per basis):
//                           C(t) = -sigma^2 (T^2 e^{-|t|/T} + T |t|)   (C'' = -sigma^2 e^{-|t|/T};
//                           evaluated without the annihilated 1 + (t/T)^2/2 when T >= tau0)
// f is linear in theta, so the covariance is a quadratic form in theta: the 15 products of the
// five unit kernels are summed once (CovarianceBasis) and any model's covariance is then a
// cheap combination of them.
// Each C reproduces its term's Allan variance (checked in tests/fit/test_covariance.cpp against
// the closed forms and the Greenhall-Riley EDF). The number of (k, l) pairs at lag delta is
// w(delta) = max(0, min(n_i, n_j + delta) - max(0, delta)). Between consecutive breakpoints
// (delta = q m_j - p m_i, and the kinks of w) f is smooth (a polynomial of degree <= 3 for N
// and K), so w f^2 is summed exactly on short pieces and, on long ones, integrated by 8-point
// Gauss-Legendre with the Euler-Maclaurin end correction (sum_{a}^{b-1} g = int_a^b g +
// (g(a) - g(b))/2 + O(g'/12)). The flicker kernel has no finite support: its tails are summed
// the same way over geometrically growing pieces until they stop contributing. The Gauss-Markov
// kernel's exponential part lives within a few T of each breakpoint: with it, long pieces are cut
// into sub-pieces growing geometrically from both ends (first length max(64, T/tau0) samples), so
// every Gauss-Legendre piece sees a smooth, slowly varying integrand.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <thread>
#include <utility>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/gmwm.hpp"

namespace imunoise::fit {
namespace {

constexpr std::array<double, 8> kGlNodes = {-0.9602898564975363, -0.7966664774136267,
                                            -0.5255324099163290, -0.1834346424956498,
                                            0.1834346424956498,  0.5255324099163290,
                                            0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGlWeights = {0.1012285362903763, 0.2223810344533745,
                                              0.3137066458778873, 0.3626837833783620,
                                              0.3626837833783620, 0.3137066458778873,
                                              0.2223810344533745, 0.1012285362903763};
constexpr std::int64_t kDirectPiece = 64;

// The five random terms (Q, N, B, K, Gauss-Markov) and their 15 products (a <= b), in the order
// (0,0) (0,1) .. (0,4) (1,1) .. (1,4) (2,2) .. (4,4).
constexpr int kRandom = 5;
constexpr int kProducts = 15;
using Products = std::array<double, kProducts>;

/// e^-x + x, less 1 + x^2/2 when T_c >= tau0 (that polynomial is annihilated by the second
/// differences, and removing it keeps the x^3/6 that matters for T_c >> lags from cancelling).
double gm_shape_subtracted(double x) {
  if (x >= 2.0) return std::exp(-x) - 1.0 + x - 0.5 * x * x;
  // -x^3/3! + x^4/4! - ...: alternating series, 25 terms reach double precision at x = 2.
  double term = -x * x * x / 6.0, sum = term;
  for (int n = 4; n < 30; ++n) {
    term *= -x / n;
    sum += term;
  }
  return sum;
}

struct PairKernel {
  using Sums = Products;
  /// The flicker kernel has the only long tails: stop when its B-B sum is converged.
  static bool tail_done(const Sums& part, const Sums& total) { return part[9] < 1e-9 * total[9]; }
  double mi, mj;  // averaging factors
  double ni, nj;  // term counts
  double tau0;
  double gm_time_s = 0.0;  // 0: no Gauss-Markov kernel

  double gm_shape(double x) const {
    return gm_time_s >= tau0 ? gm_shape_subtracted(x) : std::exp(-x) + x;
  }

  // Unit-intensity kernels f_t(delta) of the four terms (theta_t = 1).
  std::array<double, kRandom> f(double delta, bool discrete) const {
    static constexpr double cc[3] = {1.0, -2.0, 1.0};
    std::array<double, kRandom> out{};
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        const double u = delta + p * mi - q * mj;
        const double weight = cc[p] * cc[q];
        const double t = std::abs(u) * tau0;
        if (discrete && u == 0.0) out[0] += weight;
        out[1] += weight * (-0.5 * t);
        if (t > 0.0) out[2] += weight * (t * t * std::log(t) / (2.0 * std::numbers::pi));
        out[3] += weight * (t * t * t / 12.0);
        if (gm_time_s > 0.0) out[4] -= weight * gm_time_s * gm_time_s * gm_shape(t / gm_time_s);
      }
    }
    return out;
  }
  double w(double delta) const {
    return std::max(0.0, std::min(ni, nj + delta) - std::max(0.0, delta));
  }
  void add_g(double delta, bool discrete, double scale, Products& acc) const {
    const double weight = scale * w(delta);
    if (weight == 0.0) return;
    const auto v = f(delta, discrete);
    int idx = 0;
    for (int a = 0; a < kRandom; ++a) {
      for (int b = a; b < kRandom; ++b) acc[static_cast<std::size_t>(idx++)] += weight * v[static_cast<std::size_t>(a)] * v[static_cast<std::size_t>(b)];
    }
  }
  // sum_{delta = a}^{b - 1} w f_a f_b, a < b integers.
  Products piece(std::int64_t a, std::int64_t b) const {
    if (gm_time_s > 0.0 && b - a > kDirectPiece) {
      // Sub-pieces doubling away from both ends (see the header).
      const auto first = std::max<std::int64_t>(
          kDirectPiece, static_cast<std::int64_t>(std::ceil(gm_time_s / tau0)));
      std::vector<std::int64_t> cuts{a, b};
      const std::int64_t mid = a + (b - a) / 2;
      for (std::int64_t len = first, x = a + first; x < mid; len *= 2, x += len) cuts.push_back(x);
      for (std::int64_t len = first, x = b - first; x > mid; len *= 2, x -= len) cuts.push_back(x);
      std::sort(cuts.begin(), cuts.end());
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
      Products acc{};
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const Products part = smooth_piece(cuts[c], cuts[c + 1]);
        for (std::size_t i = 0; i < acc.size(); ++i) acc[i] += part[i];
      }
      return acc;
    }
    return smooth_piece(a, b);
  }
  Products smooth_piece(std::int64_t a, std::int64_t b) const {
    Products acc{};
    if (b - a <= kDirectPiece) {
      for (std::int64_t d = a; d < b; ++d) add_g(static_cast<double>(d), true, 1.0, acc);
      return acc;
    }
    const double half = 0.5 * static_cast<double>(b - a);
    const double mid = 0.5 * static_cast<double>(a + b);
    for (std::size_t k = 0; k < kGlNodes.size(); ++k) {
      add_g(mid + half * kGlNodes[k], false, half * kGlWeights[k], acc);
    }
    add_g(static_cast<double>(a), true, 0.5, acc);
    add_g(static_cast<double>(b), true, -0.5, acc);
    return acc;
  }
};

/// The AR1 (point-sampled Gauss-Markov) kernel for unit variance, without the part the second
/// differences annihilate: C(t) = -(A e^-x + B T x), x = |t| / T, written as
/// -(A s(x) + (B T - A) x) with s(x) = e^-x - 1 + x - x^2/2 when T >= tau0 (gmwm.hpp).
struct Ar1Kernel {
  double tc = 0.0;
  double a = 0.0;        // tau0^2 phi / (1 - phi)^2
  double linear = 0.0;   // B T - A (T >= tau0) or B T (T < tau0)
  bool subtracted = false;
  Ar1Kernel() = default;
  Ar1Kernel(double tc_s, double tau0_s) : tc(tc_s), subtracted(tc_s >= tau0_s) {
    const double u = 0.5 * tau0_s / tc_s;  // half of tau0 / T
    const double sh = std::sinh(u);
    a = tau0_s * tau0_s / (4.0 * sh * sh);
    const double bt = 0.5 * tau0_s * tc_s / std::tanh(u);
    if (!subtracted) {
      linear = bt;
    } else if (u < 1e-2) {
      // T^2 (u coth u - u^2 / sinh^2 u) by its series (the difference cancels).
      linear = tc_s * tc_s * u * u * (2.0 / 3.0 - 4.0 * u * u / 45.0);
    } else {
      linear = bt - a;
    }
  }
  double operator()(double t_abs) const {
    const double x = t_abs / tc;
    // e^-x below 1e-30 of the polynomial part is left out (it is below the sums' accuracy).
    if (subtracted) return -(a * (x > 70.0 ? -1.0 + x - 0.5 * x * x : gm_shape_subtracted(x)) + linear * x);
    return -(a * (x > 70.0 ? 0.0 : std::exp(-x)) + linear * x);
  }
};

/// Power-law kernels (Q, N, B, K) and up to kMaxAr1 AR1 kernels, their products a <= b.
struct CompositeKernel {
  static constexpr std::size_t kMaxRandom = 4 + GmwmCovarianceBasis::kMaxAr1;
  static constexpr std::size_t kMaxProducts = kMaxRandom * (kMaxRandom + 1) / 2;
  using Sums = std::array<double, kMaxProducts>;
  double mi, mj, ni, nj, tau0;
  std::size_t randoms = 4;
  std::array<Ar1Kernel, GmwmCovarianceBasis::kMaxAr1> ar1{};
  // A flicker mixture (BGM) in the last AR1 slot: its kernel is the w-weighted sum of these.
  std::vector<Ar1Kernel> mixture;
  std::vector<double> mixture_w;
  double finest_tc = 0.0;  // shortest correlation time (0: none)

  bool flicker = true;     // false: the flicker kernel is left out (its products are 0)
  /// Tails: the flicker kernel (power-law tail) and the AR1 kernels (e^-|t|/T beyond the
  /// breakpoints) are summed out until every diagonal product they feed has converged.
  bool tail_done(const Sums& part, const Sums& total) const {
    std::size_t idx = 0;
    for (std::size_t a = 0; a < randoms; ++a) {
      if ((a == 2 && flicker) || a >= 4) {
        if (part[idx] > 1e-9 * total[idx]) return false;
      }
      idx += randoms - a;  // (a, a) -> (a + 1, a + 1)
    }
    return true;
  }
  std::array<double, kMaxRandom> f(double delta, bool discrete) const {
    static constexpr double cc[3] = {1.0, -2.0, 1.0};
    std::array<double, kMaxRandom> out{};
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        const double u = delta + p * mi - q * mj;
        const double weight = cc[p] * cc[q];
        const double t = std::abs(u) * tau0;
        if (discrete && u == 0.0) out[0] += weight;
        out[1] += weight * (-0.5 * t);
        if (flicker && t > 0.0) out[2] += weight * (t * t * std::log(t) / (2.0 * std::numbers::pi));
        out[3] += weight * (t * t * t / 12.0);
        const std::size_t single = mixture.empty() ? randoms : randoms - 1;
        for (std::size_t g = 0; g + 4 < single; ++g) out[4 + g] += weight * ar1[g](t);
        if (!mixture.empty()) {
          double v = 0.0;
          for (std::size_t h = 0; h < mixture.size(); ++h) v += mixture_w[h] * mixture[h](t);
          out[randoms - 1] += weight * v;
        }
      }
    }
    return out;
  }
  double w(double delta) const {
    return std::max(0.0, std::min(ni, nj + delta) - std::max(0.0, delta));
  }
  void add_g(double delta, bool discrete, double scale, Sums& acc) const {
    const double weight = scale * w(delta);
    if (weight == 0.0) return;
    const auto v = f(delta, discrete);
    std::size_t idx = 0;
    for (std::size_t a = 0; a < randoms; ++a) {
      for (std::size_t b = a; b < randoms; ++b) acc[idx++] += weight * v[a] * v[b];
    }
  }
  Sums piece(std::int64_t a, std::int64_t b) const {
    if (finest_tc > 0.0 && b - a > kDirectPiece) {
      const auto first = std::max<std::int64_t>(
          kDirectPiece, static_cast<std::int64_t>(std::ceil(finest_tc / tau0)));
      std::vector<std::int64_t> cuts{a, b};
      const std::int64_t mid = a + (b - a) / 2;
      for (std::int64_t len = first, x = a + first; x < mid; len *= 2, x += len) cuts.push_back(x);
      for (std::int64_t len = first, x = b - first; x > mid; len *= 2, x -= len) cuts.push_back(x);
      std::sort(cuts.begin(), cuts.end());
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
      Sums acc{};
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const Sums part = smooth_piece(cuts[c], cuts[c + 1]);
        for (std::size_t i = 0; i < acc.size(); ++i) acc[i] += part[i];
      }
      return acc;
    }
    return smooth_piece(a, b);
  }
  Sums smooth_piece(std::int64_t a, std::int64_t b) const {
    Sums acc{};
    if (b - a <= kDirectPiece) {
      for (std::int64_t d = a; d < b; ++d) add_g(static_cast<double>(d), true, 1.0, acc);
      return acc;
    }
    const double half = 0.5 * static_cast<double>(b - a);
    const double mid = 0.5 * static_cast<double>(a + b);
    for (std::size_t k = 0; k < kGlNodes.size(); ++k) {
      add_g(mid + half * kGlNodes[k], false, half * kGlWeights[k], acc);
    }
    add_g(static_cast<double>(a), true, 0.5, acc);
    add_g(static_cast<double>(b), true, -0.5, acc);
    return acc;
  }
};

template <class Sums>
void add_to(Sums& total, const Sums& part) {
  for (std::size_t i = 0; i < total.size(); ++i) total[i] += part[i];
}

template <class Kernel>
typename Kernel::Sums pair_sum(const Kernel& kernel) {
  using Sums = typename Kernel::Sums;
  const auto mi = static_cast<std::int64_t>(kernel.mi);
  const auto mj = static_cast<std::int64_t>(kernel.mj);
  const auto ni = static_cast<std::int64_t>(kernel.ni);
  const auto nj = static_cast<std::int64_t>(kernel.nj);
  const std::int64_t lo = -nj;  // w(delta) = 0 outside (-nj, ni)
  const std::int64_t hi = ni;
  std::vector<std::int64_t> bps;
  for (std::int64_t p = 0; p < 3; ++p) {
    for (std::int64_t q = 0; q < 3; ++q) bps.push_back(q * mj - p * mi);
  }
  bps.push_back(0);
  bps.push_back(ni - nj);
  for (auto& b : bps) b = std::clamp(b, lo, hi);
  std::sort(bps.begin(), bps.end());
  bps.erase(std::unique(bps.begin(), bps.end()), bps.end());
  Sums total{};
  for (std::size_t s = 0; s + 1 < bps.size(); ++s) add_to(total, kernel.piece(bps[s], bps[s + 1]));
  kernel.add_g(static_cast<double>(bps.back()), true, 1.0, total);
  // Tails of the flicker kernel (the others vanish outside the breakpoints), outward over
  // pieces that double in length, until a piece adds less than 1e-9 of the B-B sum.
  const std::int64_t span = std::max<std::int64_t>(bps.back() - bps.front(), 8);
  std::int64_t start = bps.back() + 1;
  for (std::int64_t len = span; start < hi; len *= 2) {
    const std::int64_t end = std::min(hi, start + len);
    const Sums part = kernel.piece(start, end);
    add_to(total, part);
    if (kernel.tail_done(part, total)) break;
    start = end;
  }
  std::int64_t end = bps.front();
  for (std::int64_t len = span; end > lo; len *= 2) {
    const std::int64_t begin = std::max(lo, end - len);
    const Sums part = kernel.piece(begin, end);
    add_to(total, part);
    if (kernel.tail_done(part, total)) break;
    end = begin;
  }
  return total;
}

}  // namespace

CovarianceBasis::CovarianceBasis(std::span<const std::size_t> m_list, std::size_t n_phase,
                                 double tau0_s, double gm_time_s)
    : k_(m_list.size()), products_(m_list.size() * m_list.size() * kProducts, 0.0),
      gm_time_s_(gm_time_s) {
  for (std::size_t m : m_list) tau_s_.push_back(static_cast<double>(m) * tau0_s);
  for (std::size_t i = 0; i < k_; ++i) {
    if (m_list[i] == 0 || n_phase <= 2 * m_list[i]) {
      throw InputError("curve covariance: averaging factor " + std::to_string(m_list[i]) +
                       " leaves no term in " + std::to_string(n_phase) + " phase samples");
    }
  }
  if (!(tau0_s > 0.0)) throw InputError("curve covariance: tau0 must be positive");
  if (!(gm_time_s >= 0.0) || !std::isfinite(gm_time_s)) {
    throw InputError("curve covariance: the Gauss-Markov correlation time must be >= 0");
  }
  for (std::size_t i = 0; i < k_; ++i) {
    for (std::size_t j = i; j < k_; ++j) {
      PairKernel kernel{};
      kernel.mi = static_cast<double>(m_list[i]);
      kernel.mj = static_cast<double>(m_list[j]);
      kernel.ni = static_cast<double>(n_phase - 2 * m_list[i]);
      kernel.nj = static_cast<double>(n_phase - 2 * m_list[j]);
      kernel.tau0 = tau0_s;
      kernel.gm_time_s = gm_time_s;
      const double ti = kernel.mi * tau0_s;
      const double tj = kernel.mj * tau0_s;
      const double scale = 2.0 / (4.0 * ti * ti * tj * tj * kernel.ni * kernel.nj);
      const Products sums = pair_sum(kernel);
      for (int p = 0; p < kProducts; ++p) {
        const double v = scale * sums[static_cast<std::size_t>(p)];
        products_[(i * k_ + j) * kProducts + static_cast<std::size_t>(p)] = v;
        products_[(j * k_ + i) * kProducts + static_cast<std::size_t>(p)] = v;
      }
    }
  }
}

std::vector<double> CovarianceBasis::covariance(std::span<const double> theta,
                                                double gm_variance) const {
  if (theta.size() != static_cast<std::size_t>(kTermCount)) {
    throw InputError("curve covariance: theta needs 5 entries (Q^2, N^2, B^2, K^2, R^2)");
  }
  std::vector<double> cov(k_ * k_, 0.0);
  const double theta_r = std::max(0.0, theta[static_cast<std::size_t>(kR)]);
  for (std::size_t e = 0; e < k_ * k_; ++e) {
    // The ramp enters as the rate random walk of equal Allan variance at these taus
    // (theta_K + 1.5 R^2 tau): see the header.
    const double tau_ij = std::sqrt(tau_s_[e / k_] * tau_s_[e % k_]);
    std::array<double, kRandom> t{};
    for (int a = 0; a < kRandom - 1; ++a) t[static_cast<std::size_t>(a)] = std::max(0.0, theta[static_cast<std::size_t>(a)]);
    t[kRandom - 1] = gm_time_s_ > 0.0 ? std::max(0.0, gm_variance) : 0.0;
    t[static_cast<std::size_t>(kK)] += 1.5 * theta_r * tau_ij;
    std::array<double, kProducts> coef{};
    int idx = 0;
    for (int a = 0; a < kRandom; ++a) {
      for (int b = a; b < kRandom; ++b) {
        coef[static_cast<std::size_t>(idx++)] = (a == b ? 1.0 : 2.0) * t[static_cast<std::size_t>(a)] * t[static_cast<std::size_t>(b)];
      }
    }
    double v = 0.0;
    for (int p = 0; p < kProducts; ++p) v += coef[static_cast<std::size_t>(p)] * products_[e * kProducts + static_cast<std::size_t>(p)];
    cov[e] = v;
  }
  return cov;
}

std::vector<double> curve_covariance(std::span<const std::size_t> m_list, std::size_t n_phase,
                                     double tau0_s, std::span<const double> theta) {
  return CovarianceBasis(m_list, n_phase, tau0_s).covariance(theta);
}

GmwmCovarianceBasis::GmwmCovarianceBasis(std::span<const std::size_t> m_list, std::size_t n_phase,
                                         double tau0_s, std::span<const double> ar1_times_s,
                                         bool flicker, unsigned threads, const FlickerMixture* mixture)
    : k_(m_list.size()),
      randoms_(4 + ar1_times_s.size() + (mixture != nullptr && !mixture->empty() ? 1 : 0)),
      mixture_(mixture != nullptr && !mixture->empty()) {
  if (randoms_ - 4 > kMaxAr1) {
    throw InputError("wavelet-variance covariance: at most " + std::to_string(kMaxAr1) +
                     " Gauss-Markov terms (a flicker mixture BGM counts as one)");
  }
  if (!(tau0_s > 0.0)) throw InputError("wavelet-variance covariance: tau0 must be positive");
  for (std::size_t i = 0; i < k_; ++i) {
    if (m_list[i] == 0 || n_phase <= 2 * m_list[i]) {
      throw InputError("wavelet-variance covariance: averaging factor " + std::to_string(m_list[i]) +
                       " leaves no term in " + std::to_string(n_phase) + " phase samples");
    }
  }
  CompositeKernel base{};
  base.tau0 = tau0_s;
  base.randoms = randoms_;
  base.flicker = flicker;
  for (std::size_t g = 0; g < ar1_times_s.size(); ++g) {
    const double tc = ar1_times_s[g];
    if (!(tc > 0.0) || !std::isfinite(tc)) {
      throw InputError("wavelet-variance covariance: a Gauss-Markov correlation time must be > 0");
    }
    base.ar1[g] = Ar1Kernel(tc, tau0_s);
    base.finest_tc = base.finest_tc == 0.0 ? tc : std::min(base.finest_tc, tc);
  }
  if (mixture_) {
    for (std::size_t q = 0; q < mixture->correlation_time_s.size(); ++q) {
      const double tc = mixture->correlation_time_s[q];
      base.mixture.emplace_back(tc, tau0_s);
      base.mixture_w.push_back(mixture->variance_per_b2[q]);
      base.finest_tc = base.finest_tc == 0.0 ? tc : std::min(base.finest_tc, tc);
    }
  }
  const std::size_t products = randoms_ * (randoms_ + 1) / 2;
  products_.assign(k_ * k_ * products, 0.0);
  for (std::size_t m : m_list) tau_s_.push_back(static_cast<double>(m) * tau0_s);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < k_; ++i) {
    for (std::size_t j = i; j < k_; ++j) pairs.emplace_back(i, j);
  }
  // The pairs are independent: split over threads (the sums do not depend on the split).
  auto work = [&](std::size_t first, std::size_t stride) {
    for (std::size_t q = first; q < pairs.size(); q += stride) {
      const auto [i, j] = pairs[q];
      CompositeKernel kernel = base;
      kernel.mi = static_cast<double>(m_list[i]);
      kernel.mj = static_cast<double>(m_list[j]);
      kernel.ni = static_cast<double>(n_phase - 2 * m_list[i]);
      kernel.nj = static_cast<double>(n_phase - 2 * m_list[j]);
      const double ti = kernel.mi * tau0_s;
      const double tj = kernel.mj * tau0_s;
      const double scale = 2.0 / (4.0 * ti * ti * tj * tj * kernel.ni * kernel.nj);
      const auto sums = pair_sum(kernel);
      for (std::size_t p = 0; p < products; ++p) {
        products_[(i * k_ + j) * products + p] = scale * sums[p];
        products_[(j * k_ + i) * products + p] = scale * sums[p];
      }
    }
  };
  const unsigned workers = std::max(1u, std::min<unsigned>(threads == 0 ? std::thread::hardware_concurrency() : threads,
                                                           static_cast<unsigned>(pairs.size())));
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(work, w, workers);
  work(0, workers);
  for (auto& t : pool) t.join();
}

std::vector<double> GmwmCovarianceBasis::covariance(std::span<const double> theta,
                                                    std::span<const double> ar1_variances,
                                                    double mixture_b2) const {
  if (theta.size() != static_cast<std::size_t>(kTermCount) ||
      ar1_variances.size() + 4 + (mixture_ ? 1 : 0) != randoms_) {
    throw InputError("wavelet-variance covariance: theta needs 5 entries and one variance per "
                     "Gauss-Markov term");
  }
  const std::size_t products = randoms_ * (randoms_ + 1) / 2;
  std::vector<double> cov(k_ * k_, 0.0);
  const double theta_r = std::max(0.0, theta[static_cast<std::size_t>(kR)]);
  std::array<double, CompositeKernel::kMaxRandom> t{};
  std::array<double, CompositeKernel::kMaxProducts> coef{};
  for (std::size_t e = 0; e < k_ * k_; ++e) {
    const double tau_ij = std::sqrt(tau_s_[e / k_] * tau_s_[e % k_]);
    for (std::size_t a = 0; a < 4; ++a) t[a] = std::max(0.0, theta[a]);
    for (std::size_t g = 0; g < ar1_variances.size(); ++g) t[4 + g] = std::max(0.0, ar1_variances[g]);
    if (mixture_) t[randoms_ - 1] = std::max(0.0, mixture_b2);
    t[static_cast<std::size_t>(kK)] += 1.5 * theta_r * tau_ij;
    std::size_t idx = 0;
    for (std::size_t a = 0; a < randoms_; ++a) {
      for (std::size_t b = a; b < randoms_; ++b) coef[idx++] = (a == b ? 1.0 : 2.0) * t[a] * t[b];
    }
    double v = 0.0;
    for (std::size_t p = 0; p < products; ++p) v += coef[p] * products_[e * products + p];
    cov[e] = v;
  }
  return cov;
}

}  // namespace imunoise::fit
