// Coverage of the chi-squared intervals: over 500 simulated records each of white, flicker and
// random-walk FM, the 68.3% and 95% intervals around oadev must contain the true deviation in a
// fraction of records inside the binomial 99% band of the nominal level.
//
// Taus: m = 4, 16, 64 of 1025 phase points (EDF ~300 down to ~15), with the true noise type, and
// m = 4, 16 with the noise type identified (lag-1 ACF on >= 65 points). Measured outside this
// range and documented in docs/confidence.md, not asserted: at m = 1 the Greenhall-Riley model
// (phase samples as tau0-averages, as in Stable32) misjudges discrete-time noise (random-walk FM:
// 0.762 / 0.972, too wide; white FM 0.634 / 0.936); at m = 256 (r = M/S = 2, EDF ~4) the EDF is
// exact but the chi-squared shape is not (0.73 / 0.98, too wide); with identification at m >= 64
// only B1 (17 points) or the previous tau's type is available.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/deviation.hpp"
#include "power_law_noise.hpp"

namespace imunoise {
namespace {

constexpr std::size_t kRate = 1024;  // rate samples per record (1025 phase points), tau0 = 1
constexpr int kSeries = 500;

// True Allan variance (unit driving noise), the expectation of the overlapping estimator.
// White FM: sigma^2(m) = 1/m. Random-walk FM (y = running sum of unit white noise): the
// difference of adjacent m-averages weights the steps by a triangle min(j, 2m - j)/m, so
// sigma^2(m) = (2 m^2 + 1) / (6 m).
double true_avar_white(std::size_t m) { return 1.0 / static_cast<double>(m); }
double true_avar_random_walk(std::size_t m) {
  const double mm = static_cast<double>(m);
  return (2 * mm * mm + 1) / (6 * mm);
}

// Flicker FM: y = h * w (Kasdin-Walter, zero past), so every term of the overlapping estimator,
// D_k = sum_{i=k+m}^{k+2m-1} y_i - sum_{i=k}^{k+m-1} y_i, is sum_j g_j w_j with
// g_j = H(k+2m-1-j) - 2 H(k+m-1-j) + H(k-1-j), H(n) = h_0 + ... + h_n (0 for n < 0), and
// E[sigma_hat^2] = mean_k sum_j g_j^2 / (2 m^2) exactly (the process is not stationary, so the
// mean over k is the quantity the estimator targets).
double true_avar_flicker(const std::vector<double>& h, std::size_t m) {
  const std::size_t n = h.size();
  std::vector<double> cumulative(n);
  double s = 0;
  for (std::size_t i = 0; i < n; ++i) cumulative[i] = (s += h[i]);
  auto H = [&](long long i) { return i < 0 ? 0.0 : cumulative[static_cast<std::size_t>(i)]; };
  const std::size_t terms = n + 1 - 2 * m;
  const auto mm = static_cast<long long>(m);
  long double total = 0;
  for (std::size_t k = 0; k < terms; ++k) {
    const auto kk = static_cast<long long>(k);
    long double sum = 0;
    for (long long j = 0; j <= kk + 2 * mm - 1; ++j) {
      const double g = H(kk + 2 * mm - 1 - j) - 2 * H(kk + mm - 1 - j) + H(kk - 1 - j);
      sum += static_cast<long double>(g) * g;
    }
    total += sum;
  }
  return static_cast<double>(total / terms) / (2.0 * static_cast<double>(m * m));
}

struct Coverage {
  int inside68 = 0, inside95 = 0, alpha_right = 0;
};

// Runs kSeries records of noise `alpha`; counts intervals containing the true deviation, with
// the noise type identified (the whole pipeline) or forced to the truth.
std::vector<Coverage> coverage(int alpha, const std::vector<std::size_t>& factors,
                               const std::vector<double>& true_dev, bool identify,
                               std::uint64_t seed) {
  test::Gaussian gaussian(seed);
  std::vector<Coverage> out(factors.size());
  for (int s = 0; s < kSeries; ++s) {
    const std::vector<double> x = test::power_law_phase(alpha, kRate + 1, gaussian);
    const std::vector<DevPoint> points = compute_deviation(Estimator::oadev, x, 1.0, factors);
    for (double level : {0.683, 0.95}) {
      std::vector<DevPoint> p = points;
      ConfidenceOptions options;
      options.level = level;
      if (!identify) options.forced_alpha = alpha;
      fill_confidence(p, Estimator::oadev, x, options);
      for (std::size_t i = 0; i < factors.size(); ++i) {
        const bool inside = p[i].ci_low <= true_dev[i] && true_dev[i] <= p[i].ci_high;
        (level < 0.9 ? out[i].inside68 : out[i].inside95) += inside;
        if (level < 0.9) out[i].alpha_right += p[i].alpha == alpha;
      }
    }
  }
  return out;
}

// The binomial 99% band of the fraction of kSeries = 500 independent records inside a p-level
// interval: p +- 2.576 sqrt(p (1 - p) / 500): 0.683 +- 0.0536 and 0.95 +- 0.0251. Each (noise,
// tau, level) cell is checked against it; with fixed seeds the outcome is deterministic.
void expect_in_band(const std::vector<Coverage>& result, const std::vector<std::size_t>& factors,
                    const std::string& what) {
  for (std::size_t i = 0; i < factors.size(); ++i) {
    const double f68 = result[i].inside68 / double(kSeries);
    const double f95 = result[i].inside95 / double(kSeries);
    const double band68 = 2.576 * std::sqrt(0.683 * 0.317 / kSeries);
    const double band95 = 2.576 * std::sqrt(0.95 * 0.05 / kSeries);
    EXPECT_NEAR(f68, 0.683, band68) << what << " m = " << factors[i];
    EXPECT_NEAR(f95, 0.95, band95) << what << " m = " << factors[i];
    ::testing::Test::RecordProperty(
        what + " m=" + std::to_string(factors[i]),
        std::to_string(f68) + " / " + std::to_string(f95) + " (alpha right " +
            std::to_string(result[i].alpha_right / double(kSeries)) + ")");
  }
}

const std::vector<std::size_t> kFactors{4, 16, 64};
const std::vector<std::size_t> kIdentified{4, 16};

std::vector<double> deviations(double (*avar)(std::size_t), const std::vector<std::size_t>& f) {
  std::vector<double> dev;
  for (std::size_t m : f) dev.push_back(std::sqrt(avar(m)));
  return dev;
}

TEST(Coverage, WhiteFm) {
  expect_in_band(coverage(0, kFactors, deviations(true_avar_white, kFactors), false, 101), kFactors,
                 "white FM forced");
  expect_in_band(coverage(0, kIdentified, deviations(true_avar_white, kIdentified), true, 102),
                 kIdentified, "white FM identified");
}

TEST(Coverage, FlickerFm) {
  const std::vector<double> h = test::flicker_coefficients(kRate);
  std::vector<double> truth;
  for (std::size_t m : kFactors) truth.push_back(std::sqrt(true_avar_flicker(h, m)));
  // Sanity check of the exact expectation against the continuous-time flicker floor
  // 2 ln2 h_-1 with h_-1 = 1/pi for this filter (one-sided S_y = 1/(pi f) at low f): the
  // variance is 0.4% above it at m = 16 (5% at m = 4, -0.3% at m = 64).
  const double level = std::sqrt(2 * std::log(2.0) / 3.14159265358979);
  EXPECT_NEAR(truth[1] / level, 1.0, 0.005);
  expect_in_band(coverage(-1, kFactors, truth, false, 201), kFactors, "flicker FM forced");
  const std::vector<double> truth_identified(truth.begin(), truth.begin() + 2);
  expect_in_band(coverage(-1, kIdentified, truth_identified, true, 202), kIdentified,
                 "flicker FM identified");
}

TEST(Coverage, RandomWalkFm) {
  expect_in_band(coverage(-2, kFactors, deviations(true_avar_random_walk, kFactors), false, 301),
                 kFactors, "random-walk FM forced");
  expect_in_band(
      coverage(-2, kIdentified, deviations(true_avar_random_walk, kIdentified), true, 302),
      kIdentified, "random-walk FM identified");
}

}  // namespace
}  // namespace imunoise
