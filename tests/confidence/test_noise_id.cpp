// Noise identification: the lag-1 autocorrelation method on simulated pure power-law noise,
// the B1 and R(n) fallbacks, and the messages for short data.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "imunoise/confidence/noise_id.hpp"
#include "imunoise/error.hpp"
#include "power_law_noise.hpp"

namespace imunoise {
namespace {

// For `series` simulated phase records of noise `alpha` (n_phase points each), the fraction
// identified as alpha at each averaging factor, and by which method.
struct Outcome {
  double success = 0;
  int lag1 = 0, b1 = 0, b1_rn = 0;
};
std::vector<Outcome> success_rates(int alpha, Estimator estimator, std::size_t n_phase,
                                   const std::vector<std::size_t>& factors, int series,
                                   std::uint64_t seed) {
  test::Gaussian gaussian(seed);
  std::vector<Outcome> out(factors.size());
  std::vector<int> hits(factors.size(), 0);
  for (int s = 0; s < series; ++s) {
    const auto phase = test::power_law_phase(alpha, n_phase, gaussian);
    for (std::size_t i = 0; i < factors.size(); ++i) {
      const NoiseId id = try_identify_noise(phase, factors[i], estimator);
      hits[i] += id.alpha == alpha;
      out[i].lag1 += id.method == NoiseIdMethod::lag1_acf;
      out[i].b1 += id.method == NoiseIdMethod::b1_ratio;
      out[i].b1_rn += id.method == NoiseIdMethod::b1_rn_ratio;
    }
  }
  for (std::size_t i = 0; i < factors.size(); ++i) {
    out[i].success = static_cast<double>(hits[i]) / series;
  }
  return out;
}
Outcome success_rate(int alpha, Estimator estimator, std::size_t n_phase, std::size_t m, int series,
                     std::uint64_t seed) {
  return success_rates(alpha, estimator, n_phase, {m}, series, seed)[0];
}

TEST(NoiseId, LagOneAutocorrelationFindsEachPurePowerLaw) {
  // Requirement: the simulated alpha in >= 95% of cases at taus with enough data, here
  // n_phase = 1025 and m = 1, 2, 4, 8 (1025 .. 129 decimated points), 200 series each.
  // Measured (docs/confidence.md): 97.5-100% for every FM type at these m, except flicker-walk FM
  // at m = 2 (87.5%, excluded below). Flicker PM is identified at m = 1 only: decimating
  // flicker phase aliases it toward white PM (95% at m = 2, 76% at m = 4), a limitation of the
  // method that Stable32 shares.
  struct Case {
    int alpha;
    Estimator estimator;
    std::vector<std::size_t> factors;
  };
  const std::vector<Case> cases{
      {2, Estimator::oadev, {1, 2, 4, 8}},  {1, Estimator::oadev, {1}},
      {0, Estimator::oadev, {1, 2, 4, 8}},  {-1, Estimator::oadev, {1, 2, 4, 8}},
      {-2, Estimator::oadev, {1, 2, 4, 8}}, {0, Estimator::mdev, {1, 4}},
      {-2, Estimator::ohdev, {1, 2, 4, 8}}, {-3, Estimator::ohdev, {1, 4, 8}},
      {-4, Estimator::ohdev, {1, 2, 4, 8}},
  };
  for (const Case& c : cases) {
    const auto out = success_rates(c.alpha, c.estimator, 1025, c.factors, 200, 4242 + c.alpha);
    for (std::size_t i = 0; i < c.factors.size(); ++i) {
      EXPECT_GE(out[i].success, 0.95)
          << "alpha " << c.alpha << " m " << c.factors[i] << " " << estimator_name(c.estimator);
      EXPECT_EQ(out[i].lag1, 200);
      RecordProperty("alpha" + std::to_string(c.alpha) + "_" +
                         std::string(estimator_name(c.estimator)) + "_m" +
                         std::to_string(c.factors[i]),
                     std::to_string(out[i].success));
    }
  }
}

TEST(NoiseId, ShortDataFallsBackToB1AndRn) {
  // Fewer than 30 decimated points: B1, and B1 + R(n) when B1 says PM. With 24-25 points these
  // are rough. Measured (200 series): white FM 82% (25 points, m = 1), random-walk FM 78% and
  // flicker FM 79% (101 points, m = 4), white PM 90% and flicker PM 69% (mdev, m = 4). The bounds
  // sit ~4 binomial standard deviations (0.03 at 200 series) below the measured rates.
  const Outcome white_fm = success_rate(0, Estimator::oadev, 25, 1, 200, 7);
  EXPECT_EQ(white_fm.b1 + white_fm.b1_rn, 200);
  EXPECT_GE(white_fm.success, 0.70);
  const Outcome rw_fm = success_rate(-2, Estimator::oadev, 101, 4, 200, 8);
  EXPECT_EQ(rw_fm.b1, 200);
  EXPECT_GE(rw_fm.success, 0.66);
  const Outcome white_pm = success_rate(2, Estimator::mdev, 101, 4, 200, 9);
  EXPECT_GE(white_pm.b1_rn, 150);
  EXPECT_GE(white_pm.success, 0.80);
}

TEST(NoiseId, B1Expectations) {
  // Barnes' bias function B1(N, mu) = N (1 - N^mu) / (2 (N - 1) (1 - 2^mu)).
  EXPECT_NEAR(b1_expected(10, -1), 1.0, 1e-15);  // white FM: the N-sample variance is unbiased
  EXPECT_NEAR(b1_expected(10, 1), 5.0, 1e-12);   // random-walk FM: N/2
  EXPECT_NEAR(b1_expected(10, -2), 11.0 / 15.0, 1e-15);  // PM: (N + 1) / (1.5 N)
  EXPECT_NEAR(b1_expected(10, 0), 10 * std::log(10.0) / (18 * std::log(2.0)), 1e-14);
  EXPECT_NEAR(b1_expected(10, 1e-9), b1_expected(10, 0), 1e-6);  // continuous in mu
  EXPECT_NEAR(b1_expected(10, 2), 10.0 * 11.0 / 6.0, 1e-12);     // N (N + 1) / 6

  // The measured ratio of a long white-FM record is close to 1.
  test::Gaussian gaussian(3);
  const auto phase = test::power_law_phase(0, 20001, gaussian);
  EXPECT_NEAR(b1_ratio(phase, 1), 1.0, 0.05);  // sd ~ sqrt(2/N) = 0.01
}

TEST(NoiseId, RnExpectationsMatchTheLiterature) {
  // Mod sigma^2 / sigma^2: white PM 1/m exactly; for large m white FM 0.50, flicker FM 0.67,
  // random-walk FM 0.82 (NIST TN 1337, table of R(n)); flicker PM ~3.37/(1.04 + 3 ln(pi m)).
  for (std::size_t m : {1u, 2u, 7u, 64u})
    EXPECT_NEAR(rn_expected(2, m), 1.0 / static_cast<double>(m), 1e-12);
  EXPECT_NEAR(rn_expected(0, 4096), 0.50, 0.005);
  EXPECT_NEAR(rn_expected(-1, 4096), 0.67, 0.01);
  EXPECT_NEAR(rn_expected(-2, 4096), 0.82, 0.01);
  for (std::size_t m : {8u, 64u, 1024u}) {
    EXPECT_NEAR(rn_expected(1, m),
                3.37 / (1.04 + 3 * std::log(3.14159265358979 * static_cast<double>(m))), 0.05)
        << m;
  }
  EXPECT_TRUE(std::isnan(rn_expected(-3, 4)));
  // Measured on white PM: close to 1/m.
  test::Gaussian gaussian(5);
  const auto phase = test::power_law_phase(2, 40001, gaussian);
  EXPECT_NEAR(rn_ratio(phase, 8), 1.0 / 8, 0.01);
}

TEST(NoiseId, Lag1AutocorrelationBasics) {
  const std::vector<double> ramp{1, 2, 3};
  EXPECT_DOUBLE_EQ(lag1_autocorrelation(ramp), 0.0);  // (-1)(0) + (0)(1) over 2
  const std::vector<double> alternating{1, -1, 1, -1, 1, -1, 1, -1};
  EXPECT_NEAR(lag1_autocorrelation(alternating), -7.0 / 8.0, 1e-15);
  const std::vector<double> constant(10, 3.0);
  EXPECT_TRUE(std::isnan(lag1_autocorrelation(constant)));
  EXPECT_TRUE(std::isnan(lag1_autocorrelation(std::vector<double>{1, 2})));
  // White phase: the unrounded estimate is near 2; Brownian phase (white FM): near 0.
  test::Gaussian gaussian(11);
  EXPECT_NEAR(lag1_acf_alpha_estimate(test::power_law_phase(2, 4001, gaussian), 1, 2), 2.0, 0.1);
  EXPECT_NEAR(lag1_acf_alpha_estimate(test::power_law_phase(0, 4001, gaussian), 1, 2), 0.0, 0.1);
}

TEST(NoiseId, TooFewSamplesSaySoClearly) {
  const std::vector<double> phase{0, 1, 3, 2, 5, 4, 7, 6, 9, 8};  // 10 points
  try {
    identify_noise(phase, 4, Estimator::oadev);  // 3 points at stride 4
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("too few samples for noise identification (oadev at m = 4)"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("10 phase points give 3"), std::string::npos) << what;
    EXPECT_NE(what.find("--noise-type"), std::string::npos) << what;
  }
  const NoiseId quiet = try_identify_noise(phase, 4, Estimator::oadev);
  EXPECT_FALSE(quiet.identified());
  EXPECT_EQ(quiet.method, NoiseIdMethod::none);
  EXPECT_FALSE(quiet.message.empty());
  EXPECT_TRUE(identify_noise(phase, 1, Estimator::oadev).identified());  // 10 points: B1

  EXPECT_THROW(identify_noise(phase, 0, Estimator::oadev), InputError);
  EXPECT_THROW(try_identify_noise(phase, 0, Estimator::oadev), InputError);
  const std::vector<double> constant(100, 1.0);
  const NoiseId flat = try_identify_noise(constant, 1, Estimator::oadev);
  EXPECT_FALSE(flat.identified());
  EXPECT_NE(flat.message.find("constant"), std::string::npos);
  EXPECT_EQ(noise_id_method_name(NoiseIdMethod::previous_tau), "previous-tau");
}

TEST(NoiseId, IdentifiableIsExactlyWhenTryIdentifyDoesNotReportTooFew) {
  // fill_confidence skips the identification where noise_identifiable says no: both must agree
  // at every m, and the sentence must be the one try_identify_noise gives.
  test::Gaussian gaussian(5);
  for (const std::size_t n : {1u, 2u, 9u, 10u, 37u, 64u, 65u}) {
    const std::vector<double> phase = test::power_law_phase(0, n, gaussian);
    for (std::size_t m = 1; m <= n + 1; ++m) {
      const NoiseId id = try_identify_noise(phase, m, Estimator::oadev);
      const bool too_few = id.message.find("too few samples") != std::string::npos;
      EXPECT_EQ(noise_identifiable(n, m), !too_few) << "n = " << n << ", m = " << m;
      if (too_few) EXPECT_EQ(id.message, too_few_for_noise_id(Estimator::oadev, n, m));
    }
  }
}

}  // namespace
}  // namespace imunoise
