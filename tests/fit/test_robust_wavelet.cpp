// Robust GMWM (include/imunoise/fit/robust_wavelet.hpp, GmwmOptions::robust): the biweight's
// constants, its Fisher consistency at the Gaussian (robust wavelet variance of white noise
// against the closed form), agreement with the classical fit on a clean record and resistance
// to outliers, on records of the tests' own generator (gmwm_test_support.hpp, no src/sim code).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "fit/gmwm_test_support.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/gmwm.hpp"
#include "imunoise/fit/robust_wavelet.hpp"

namespace imunoise::fit {
namespace robust_test {

TEST(RobustWavelet, BiweightConstants) {
  // Reference values by adaptive quadrature outside this code (scipy.integrate.quad, 2026-12-03):
  // e(c) = E[Z rho'(Z)]^2 / (2 E[(rho(Z) - delta)^2]); 60 %: c = 1.72947, delta = 0.45611;
  // 80 %: c = 2.50328, delta = 0.30866; c = 3: e = 0.87727.
  const Biweight b60 = biweight_for_efficiency(0.6);
  EXPECT_NEAR(b60.c, 1.72947, 2e-5);
  EXPECT_NEAR(b60.delta, 0.45611, 2e-5);
  EXPECT_NEAR(b60.efficiency, 0.6, 1e-9);
  const Biweight b80 = biweight_for_efficiency(0.8);
  EXPECT_NEAR(b80.c, 2.50328, 2e-5);
  EXPECT_NEAR(b80.delta, 0.30866, 2e-5);
  EXPECT_NEAR(biweight_scale_efficiency(3.0), 0.87727, 2e-5);
  EXPECT_THROW(biweight_for_efficiency(0.3), InputError);
  EXPECT_THROW(biweight_for_efficiency(1.0), InputError);
}

TEST(RobustWavelet, ScaleOfGaussianValuesIsConsistent) {
  // 2^20 independent N(0, 3^2) values: the M-estimate of s^2 within 4 of its standard errors,
  // s^2 sqrt(2 / (e n)) (asymptotic variance over the efficiency e).
  gmwm_test::Normals normal(11);
  std::vector<double> x(std::size_t{1} << 20);
  for (double& v : x) v = 3.0 * normal();
  const Biweight b = biweight_for_efficiency(0.6);
  const double s2 = biweight_scale2(x, b);
  const double se = 9.0 * std::sqrt(2.0 / (b.efficiency * static_cast<double>(x.size())));
  EXPECT_NEAR(s2, 9.0, 4.0 * se);
  EXPECT_THROW(biweight_scale2(std::span<const double>(), b), InputError);
}

/// Phase (x_0 = 0, x_k = tau0 * cumulative rate) of a rate record.
std::vector<double> robust_phase(const std::vector<double>& rate, double tau0) {
  std::vector<double> phase(rate.size() + 1, 0.0);
  long double acc = 0.0L;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    acc += static_cast<long double>(rate[i] * tau0);
    phase[i + 1] = static_cast<double>(acc);
  }
  return phase;
}

TEST(RobustWavelet, WhiteNoiseWaveletVarianceIsUnbiased) {
  // White rate noise N (per-sample sd N / sqrt(tau0)): AVAR(m) = N^2 / tau exactly. Over 8
  // records of 2^20 samples (8 million coefficients per scale) the mean robust estimate must be
  // within 4 standard errors of the closed form, the standard error from the records' scatter.
  const double tau0 = 0.01, n_coef = 1e-3;
  const std::vector<std::size_t> ms{1, 2, 8, 32, 128};
  const Biweight b = biweight_for_efficiency(0.6);
  std::vector<std::vector<double>> ratio(ms.size());
  for (int rec = 0; rec < 8; ++rec) {
    const auto rate = gmwm_test::make_rate(std::size_t{1} << 20, tau0, n_coef, 0.0, {}, 300 + static_cast<std::uint64_t>(rec));
    const auto a = robust_avar(robust_phase(rate, tau0), tau0, ms, b);
    for (std::size_t i = 0; i < ms.size(); ++i) {
      ratio[i].push_back(a[i] / (n_coef * n_coef * gmwm_avar_white(static_cast<double>(ms[i]) * tau0)));
    }
  }
  for (std::size_t i = 0; i < ms.size(); ++i) {
    double mean = 0.0, sq = 0.0;
    for (double v : ratio[i]) mean += v;
    mean /= static_cast<double>(ratio[i].size());
    for (double v : ratio[i]) sq += (v - mean) * (v - mean);
    const double se = std::sqrt(sq / static_cast<double>(ratio[i].size() - 1) / static_cast<double>(ratio[i].size()));
    std::printf("m %zu: robust / exact %.5f (se %.5f)\n", ms[i], mean, se);
    EXPECT_NEAR(mean, 1.0, 4.0 * se + 1e-4) << "m " << ms[i];
  }
}

/// The robust and the classical GMWM fit of one record (N only).
struct RobustPair {
  GmwmResult classical, robust;
};
RobustPair fit_both(const std::vector<double>& rate, double tau0, const char* terms) {
  const auto c = gmwm_test::octave_curve(rate, tau0);
  const auto phase = robust_phase(rate, tau0);
  GmwmOptions o;
  parse_gmwm_terms(terms, o);
  RobustPair p;
  p.classical = fit_gmwm(c.m, c.avar, c.n_phase, tau0, o);
  o.robust = true;
  p.robust = fit_gmwm(c.m, c.avar, c.n_phase, tau0, o, phase);
  return p;
}

constexpr double kRobustTau0 = 0.01;
constexpr double kRobustN = 1.7e-4;
constexpr std::size_t kRobustSamples = 360000;  // 1 h at 100 Hz

TEST(RobustGmwm, AgreesWithTheClassicalFitOnACleanRecord) {
  // Gaussian white noise: both estimate the same N; the robust estimate's interval (widened by
  // 1 / sqrt(efficiency)) must contain the classical estimate and the truth.
  const auto rate = gmwm_test::make_rate(kRobustSamples, kRobustTau0, kRobustN, 0.0, {}, 41);
  const RobustPair p = fit_both(rate, kRobustTau0, "N");
  ASSERT_EQ(p.robust.status, GmwmStatus::converged) << p.robust.message;
  const Coefficient& nr = p.robust.terms[0].magnitude;
  const Coefficient& nc = p.classical.terms[0].magnitude;
  std::printf("clean: classical N %.6g [%.6g, %.6g]; robust N %.6g [%.6g, %.6g]\n", nc.value, nc.ci_low, nc.ci_high,
              nr.value, nr.ci_low, nr.ci_high);
  EXPECT_TRUE(p.robust.robust);
  EXPECT_NEAR(p.robust.robust_efficiency, 0.6, 1e-9);
  EXPECT_LE(nr.ci_low, nc.value);
  EXPECT_GE(nr.ci_high, nc.value);
  EXPECT_LE(nr.ci_low, kRobustN);
  EXPECT_GE(nr.ci_high, kRobustN);
  // The widening: the robust log-interval is 1 / sqrt(0.6) = 1.29 times the classical one.
  EXPECT_NEAR(std::log(nr.ci_high / nr.ci_low) / std::log(nc.ci_high / nc.ci_low), 1.0 / std::sqrt(0.6), 0.05);
}

/// A clean record (seed 42) with a fraction of its samples replaced by spikes of +-amplitude
/// sigma, at positions and signs from the test's own generator (|Z| above the two-sided
/// quantile of the fraction).
std::vector<double> spiked_record(double fraction, double amplitude, double quantile) {
  auto rate = gmwm_test::make_rate(kRobustSamples, kRobustTau0, kRobustN, 0.0, {}, 42);
  const double sigma = kRobustN / std::sqrt(kRobustTau0);
  gmwm_test::Normals pick(43);
  std::size_t spikes = 0;
  for (double& v : rate) {
    const double z = pick();
    if (std::abs(z) > quantile) {
      v = (z > 0 ? amplitude : -amplitude) * sigma;
      ++spikes;
    }
  }
  std::printf("%zu spikes (%.3g %% asked) of %g sigma in %zu samples\n", spikes, 100.0 * fraction, amplitude,
              rate.size());
  return rate;
}

TEST(RobustGmwm, ResistsOutliers) {
  // 0.1 % of the samples replaced by spikes of +-50 sigma (P(|Z| > 3.2905) = 1e-3): they add
  // 2.5 sigma^2 of white variance, so the classical N is off by ~sqrt(3.5) = 1.87. The robust
  // estimate removes them at the short scales, where a spike is many coefficient sds; at
  // m >~ 256 a window holds about one spike of 50 / sqrt(2 m) <~ 2.2 coefficient sds, which no
  // bounded-influence estimate of scale can tell from the Gaussian, so those scales keep most of
  // the spikes' variance. Measured: classical N +89 %, robust +1.5 % (its interval +-0.3 %:
  // missed), and the J test rejects the robust fit (J ~ 2800 on 17): the residual misfit is
  // flagged, not hidden. Asserted: robust error below 1/20 of the classical one, below 3 %, and
  // the rejection.
  {
    const RobustPair p = fit_both(spiked_record(1e-3, 50.0, 3.2905), kRobustTau0, "N");
    const Coefficient& nr = p.robust.terms[0].magnitude;
    const Coefficient& nc = p.classical.terms[0].magnitude;
    std::printf("0.1 %%: classical N %.6g [%.6g, %.6g]; robust N %.6g [%.6g, %.6g], J %.1f on %zu\n", nc.value,
                nc.ci_low, nc.ci_high, nr.value, nr.ci_low, nr.ci_high, p.robust.j_statistic, p.robust.dof);
    EXPECT_GT(nc.value / kRobustN, 1.5);
    EXPECT_LT(std::abs(nr.value / kRobustN - 1.0), 0.05 * std::abs(nc.value / kRobustN - 1.0));
    EXPECT_LT(std::abs(nr.value / kRobustN - 1.0), 0.03);
    EXPECT_LT(p.robust.j_p_value, 1e-3);
  }
  // 0.01 % of the samples, +-100 sigma (P(|Z| > 3.8906) = 1e-4): classical N off by ~sqrt(2);
  // the spikes stay isolated (2 m 1e-4 < 1 per window) up to m ~ 2000, where they are still
  // 100 / sqrt(2 m) ~ 1.6 sds. The robust N must lie within its interval of the truth.
  {
    const RobustPair p = fit_both(spiked_record(1e-4, 100.0, 3.8906), kRobustTau0, "N");
    const Coefficient& nr = p.robust.terms[0].magnitude;
    const Coefficient& nc = p.classical.terms[0].magnitude;
    std::printf("0.01 %%: classical N %.6g [%.6g, %.6g]; robust N %.6g [%.6g, %.6g], J %.1f on %zu\n", nc.value,
                nc.ci_low, nc.ci_high, nr.value, nr.ci_low, nr.ci_high, p.robust.j_statistic, p.robust.dof);
    EXPECT_GT(nc.value / kRobustN, 1.3);
    EXPECT_LE(nr.ci_low, kRobustN);
    EXPECT_GE(nr.ci_high, kRobustN);
  }
}

TEST(RobustGmwm, NeedsTheSamples) {
  const auto rate = gmwm_test::make_rate(4096, kRobustTau0, kRobustN, 0.0, {}, 5);
  const auto c = gmwm_test::octave_curve(rate, kRobustTau0);
  GmwmOptions o;
  parse_gmwm_terms("N", o);
  o.robust = true;
  EXPECT_THROW(fit_gmwm(c.m, c.avar, c.n_phase, kRobustTau0, o), InputError);
  o.robust_efficiency = 0.2;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
}

}  // namespace robust_test
}  // namespace imunoise::fit
