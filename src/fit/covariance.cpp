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
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"

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

void add_to(Products& total, const Products& part) {
  for (std::size_t i = 0; i < total.size(); ++i) total[i] += part[i];
}

Products pair_sum(const PairKernel& kernel) {
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
  Products total{};
  for (std::size_t s = 0; s + 1 < bps.size(); ++s) add_to(total, kernel.piece(bps[s], bps[s + 1]));
  kernel.add_g(static_cast<double>(bps.back()), true, 1.0, total);
  // Tails of the flicker kernel (the others vanish outside the breakpoints), outward over
  // pieces that double in length, until a piece adds less than 1e-9 of the B-B sum.
  constexpr std::size_t kBB = 9;  // (2,2)
  const std::int64_t span = std::max<std::int64_t>(bps.back() - bps.front(), 8);
  std::int64_t start = bps.back() + 1;
  for (std::int64_t len = span; start < hi; len *= 2) {
    const std::int64_t end = std::min(hi, start + len);
    const Products part = kernel.piece(start, end);
    add_to(total, part);
    if (part[kBB] < 1e-9 * total[kBB]) break;
    start = end;
  }
  std::int64_t end = bps.front();
  for (std::int64_t len = span; end > lo; len *= 2) {
    const std::int64_t begin = std::max(lo, end - len);
    const Products part = kernel.piece(begin, end);
    add_to(total, part);
    if (part[kBB] < 1e-9 * total[kBB]) break;
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

}  // namespace imunoise::fit
