// The analytic covariance of the overlapping Allan variance curve (fit/fit.hpp,
// curve_covariance): its diagonal against the Greenhall-Riley EDF (an independent derivation
// of the same variance) and its correlations against a small Monte-Carlo.
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "imunoise/allan.hpp"
#include "imunoise/confidence/edf.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/sim/generator.hpp"

namespace {

using imunoise::fit::curve_covariance;

// Var(s) = 2 sigma^4 / edf for each pure noise type (Greenhall & Riley, oadev). Their model
// (continuous-time phase) differs from the sampled one at small m by up to ~17%, so the check
// starts at m = 64 where both agree; small m is checked exactly below for white rate noise.
void check_diagonal(int term, int alpha, double tolerance) {
  const std::size_t n_phase = 20001;
  const double tau0 = 0.01;
  const std::vector<std::size_t> m = {64, 500, 2000};
  std::vector<double> theta(5, 0.0);
  theta[static_cast<std::size_t>(term)] = 2.5;
  const auto cov = curve_covariance(m, n_phase, tau0, theta);
  const imunoise::DifferenceVariance oadev{2, false, true};
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double tau = static_cast<double>(m[i]) * tau0;
    const double avar = theta[static_cast<std::size_t>(term)] * imunoise::fit::term_basis(term, tau);
    const double edf = imunoise::greenhall_riley_edf(alpha, oadev, m[i], n_phase);
    const double expected = 2.0 * avar * avar / edf;
    EXPECT_NEAR(cov[i * m.size() + i] / expected, 1.0, tolerance)
        << "term " << imunoise::fit::term_name(term) << " m = " << m[i];
  }
}

TEST(CurveCovariance, DiagonalMatchesGreenhallRileyWhiteRate) { check_diagonal(imunoise::fit::kN, 0, 0.01); }

TEST(CurveCovariance, WhiteRateExactAtSmallFactors) {
  // White rate samples of variance 1 (tau0 = 1): a_k = sum of m later minus m earlier samples,
  // Cov(a_k, a_k+d) = 2m - 3|d| (|d| <= m), |d| - 2m (m < |d| <= 2m), 0 beyond; so
  // Var(s) = 2 sum_d (n - |d|) c(d)^2 / (4 m^4 n^2) exactly.
  const std::size_t n_phase = 2001;
  for (std::size_t m : {1, 2, 3, 8, 30}) {
    const auto mi = static_cast<long>(m);
    const double n = static_cast<double>(n_phase - 2 * m);
    double s = 0.0;
    for (long d = -2 * mi; d <= 2 * mi; ++d) {
      const long a = d < 0 ? -d : d;
      const double c = a <= mi ? static_cast<double>(2 * mi - 3 * a) : static_cast<double>(a - 2 * mi);
      s += (n - static_cast<double>(a)) * c * c;
    }
    const double md = static_cast<double>(m);
    const double expected = 2.0 * s / (4.0 * md * md * md * md * n * n);
    const std::vector<std::size_t> ml = {m};
    const auto cov = curve_covariance(ml, n_phase, 1.0, std::vector<double>{0, 1, 0, 0, 0});
    EXPECT_NEAR(cov[0] / expected, 1.0, 1e-12) << "m = " << m;
  }
}
TEST(CurveCovariance, DiagonalMatchesGreenhallRileyRateRandomWalk) {
  check_diagonal(imunoise::fit::kK, -2, 0.01);
}
TEST(CurveCovariance, DiagonalMatchesGreenhallRileyFlicker) {
  // Greenhall-Riley's flicker model differs slightly from the ideal t^2 ln t kernel at small m.
  check_diagonal(imunoise::fit::kB, -1, 0.05);
}

// Sample means and second moments of the oadev estimates at m over `runs` simulated records.
struct CurveMoments {
  std::vector<double> sum, sum2;
  int runs = 0;
  double mean(std::size_t i) const { return sum[i] / runs; }
  double cov(std::size_t i, std::size_t j) const {
    return sum2[i * sum.size() + j] / runs - mean(i) * mean(j);
  }
};

CurveMoments monte_carlo(const imunoise::sim::NoiseModel& model, double rate, std::size_t n_rate,
                         const std::vector<std::size_t>& m, int runs, std::uint64_t seed0) {
  const std::size_t k = m.size();
  CurveMoments out{std::vector<double>(k, 0.0), std::vector<double>(k * k, 0.0), runs};
  for (int r = 0; r < runs; ++r) {
    const auto y = imunoise::sim::simulate(model, rate, n_rate, seed0 + static_cast<std::uint64_t>(r));
    const auto x = imunoise::phase_from_rate(y, 1.0 / rate, 0.0);
    const auto pts = imunoise::oadev(x, 1.0 / rate, m);
    for (std::size_t i = 0; i < k; ++i) {
      const double vi = pts[i].dev * pts[i].dev;
      out.sum[i] += vi;
      for (std::size_t j = 0; j < k; ++j) out.sum2[i * k + j] += vi * pts[j].dev * pts[j].dev;
    }
  }
  return out;
}

TEST(CurveCovariance, CorrelationsMatchMonteCarlo) {
  // White rate noise plus rate random walk; 400 short records.
  imunoise::sim::NoiseModel model;
  model.n_unit_sqrt_s = 1.0;
  model.k_unit_per_sqrt_s = 0.3;
  const double rate = 10.0;
  const std::size_t n_rate = 4000;
  const std::vector<std::size_t> m = {1, 2, 4, 8, 16, 32, 64};
  const std::size_t k = m.size();
  const auto mcm = monte_carlo(model, rate, n_rate, m, 400, 1000);
  const std::vector<double> theta = {0.0, 1.0, 0.0, 0.09, 0.0};
  const auto cov = curve_covariance(m, n_rate + 1, 1.0 / rate, theta);
  auto mc = [&](std::size_t i, std::size_t j) { return mcm.cov(i, j); };
  for (std::size_t i = 0; i < k; ++i) {
    // Variance: the sample variance of 400 draws is within ~3 * sqrt(2/400) = 21%.
    EXPECT_NEAR(mc(i, i) / cov[i * k + i], 1.0, 0.25) << "m = " << m[i];
    for (std::size_t j = i + 1; j < k; ++j) {
      const double rho = cov[i * k + j] / std::sqrt(cov[i * k + i] * cov[j * k + j]);
      const double rho_mc = mc(i, j) / std::sqrt(mc(i, i) * mc(j, j));
      // Standard error of a sample correlation ~ (1 - rho^2)/sqrt(n) <= 0.05.
      EXPECT_NEAR(rho_mc, rho, 0.15) << "m = " << m[i] << ", " << m[j];
    }
  }
}

TEST(CurveCovariance, GaussMarkovKernelReachesItsLimits) {
  // T << tau0: white rate noise with N^2 = 2 sigma^2 T; T >> the record: a rate random walk
  // with K^2 = 2 sigma^2 / T (the next terms are O(T / tau0) and O(record / T) relative).
  const std::size_t n_phase = 200001;
  const double tau0 = 0.01;
  const std::vector<std::size_t> m = {1, 16, 256, 4096, 40000};
  const std::size_t k = m.size();
  const std::vector<double> none(5, 0.0);
  for (const double tc : {1e-7, 1e7}) {
    const imunoise::fit::CovarianceBasis gm(m, n_phase, tau0, tc);
    const auto cov = gm.covariance(none, 1.0);
    std::vector<double> theta(5, 0.0);
    theta[tc < tau0 ? imunoise::fit::kN : imunoise::fit::kK] = tc < tau0 ? 2.0 * tc : 2.0 / tc;
    const auto expected = curve_covariance(m, n_phase, tau0, theta);
    for (std::size_t i = 0; i < k * k; ++i) {
      EXPECT_NEAR(cov[i] / expected[i], 1.0, 1e-3) << "T_c = " << tc << ", entry " << i;
    }
  }
}

TEST(CurveCovariance, GaussMarkovMatchesMonteCarlo) {
  // Gauss-Markov (T_c = 0.5 s) plus white rate noise, 400 short records at 10 Hz: taus from
  // well below to well above T_c.
  imunoise::sim::NoiseModel model;
  model.n_unit_sqrt_s = 0.3;
  model.gm_sigma_unit = 1.0;
  model.gm_time_s = 0.5;
  const double rate = 10.0;
  const std::size_t n_rate = 4000;
  const std::vector<std::size_t> m = {1, 2, 4, 8, 16, 32, 64};
  const std::size_t k = m.size();
  const auto mcm = monte_carlo(model, rate, n_rate, m, 400, 5000);
  const imunoise::fit::CovarianceBasis basis(m, n_rate + 1, 1.0 / rate, model.gm_time_s);
  const auto cov = basis.covariance(std::vector<double>{0.0, 0.09, 0.0, 0.0, 0.0}, 1.0);
  auto mc = [&](std::size_t i, std::size_t j) { return mcm.cov(i, j); };
  for (std::size_t i = 0; i < k; ++i) {
    // Mean: the Allan variance of the model (closed forms) within 4 standard errors.
    const double tau = static_cast<double>(m[i]) / rate;
    const double avar = 0.09 / tau + imunoise::fit::gauss_markov_basis(model.gm_time_s, tau);
    EXPECT_NEAR(mcm.mean(i) / avar, 1.0, 4.0 * std::sqrt(cov[i * k + i] / mcm.runs) / avar);
    // Variance and correlations: the bounds of the test above.
    EXPECT_NEAR(mc(i, i) / cov[i * k + i], 1.0, 0.25) << "m = " << m[i];
    for (std::size_t j = i + 1; j < k; ++j) {
      const double rho = cov[i * k + j] / std::sqrt(cov[i * k + i] * cov[j * k + j]);
      const double rho_mc = mc(i, j) / std::sqrt(mc(i, i) * mc(j, j));
      EXPECT_NEAR(rho_mc, rho, 0.15) << "m = " << m[i] << ", " << m[j];
    }
  }
}

}  // namespace
