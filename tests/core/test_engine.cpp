// The engine against the definitions, closed forms and its own invariances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/reference_estimators.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise {
namespace {

// Uniform noise from a fixed-seed engine: std::uniform_real_distribution is not used because
// its output differs between standard libraries; this transform is exact and portable.
std::vector<double> noise(std::size_t n, std::uint64_t seed, double scale) {
  std::mt19937_64 engine(seed);
  std::vector<double> y(n);
  for (auto& v : y) v = scale * (static_cast<double>(engine() >> 11) * 0x1.0p-53 - 0.5);
  return y;
}

std::vector<double> phase_of(const std::vector<double>& rate, double tau0) {
  return phase_from_rate(rate, tau0, compensated_mean(rate));
}

std::vector<double> devs(Estimator e, const std::vector<double>& phase, double tau0,
                         const std::vector<std::size_t>& factors, unsigned threads = 0) {
  std::vector<double> out;
  for (const auto& p : compute_deviation(e, phase, tau0, factors, {threads})) out.push_back(p.dev);
  return out;
}

class EveryEstimator : public ::testing::TestWithParam<Estimator> {};

// Every factor in the domain of a 301-point series, against the naive definition. The engine
// forms terms in double and sums in blocks; the reference works in long double throughout, so
// agreement is limited by double rounding of the terms (observed ~1e-15; 1e-12 allows for the
// cancellation at large m).
TEST_P(EveryEstimator, MatchesDefinitionForEveryFactor) {
  const Estimator e = GetParam();
  const auto phase = phase_of(noise(300, 11, 1.0), 0.01);
  const std::size_t max_m = max_averaging_factor(e, phase.size());
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= max_m; ++m) factors.push_back(m);
  const auto points = compute_deviation(e, phase, 0.01, factors);
  ASSERT_EQ(points.size(), max_m);
  for (const auto& p : points) {
    EXPECT_NEAR(p.dev / test::reference_deviation(e, phase, 0.01, p.m), 1.0, 1e-12)
        << estimator_name(e) << " m=" << p.m;
    EXPECT_EQ(p.n, term_count(e, phase.size(), p.m));
    EXPECT_DOUBLE_EQ(p.tau_s, 0.01 * static_cast<double>(p.m));
  }
}

// Every factor of a longer record: consecutive factors run eight at a time through the shared
// window kernel (AVX-512 machines) over several blocks of starts, with the smaller factors'
// extra starts at the record's end done one factor at a time; both against the definition.
TEST(EveryFactor, LongerRecordMatchesDefinition) {
  for (const Estimator e : {Estimator::oadev, Estimator::ohdev}) {
    // Exactly as long as the record (capacity == size): a kernel reading past the last sample
    // is a heap overflow for the sanitizer build, not a read into spare capacity.
    const auto built = phase_of(noise(4099, 17, 1.0), 0.01);
    const std::vector<double> phase(built.begin(), built.end());
    const std::size_t max_m = max_averaging_factor(e, phase.size());
    std::vector<std::size_t> factors;
    for (std::size_t m = 1; m <= max_m; ++m) factors.push_back(m);
    for (const auto& p : compute_deviation(e, phase, 0.01, factors)) {
      EXPECT_NEAR(p.dev / test::reference_deviation(e, phase, 0.01, p.m), 1.0, 1e-12)
          << estimator_name(e) << " m=" << p.m;
    }
  }
}

// Long records take a second path for factors that are multiples of a power-of-two column
// count (cache tiles); check it, and the ragged end of the record, against the definition.
TEST(OverlappingTiles, MatchDefinitionOnLongRecordWithOctaveFactors) {
  for (const Estimator e : {Estimator::oadev, Estimator::ohdev})
  for (const std::size_t n : {300007u, 262144u, 262145u}) {
    const auto phase = phase_of(noise(n, 15, 1.0), 0.005);
    const auto factors = averaging_factors(TauGrid{}, 200, max_averaging_factor(e, phase.size()));
    for (const auto& p : compute_deviation(e, phase, 0.005, factors)) {
      EXPECT_NEAR(p.dev / test::reference_deviation(e, phase, 0.005, p.m), 1.0, 1e-12)
          << estimator_name(e) << " n=" << n << " m=" << p.m;
    }
  }
}

// A constant rate offset 1e4 times the noise must not change any deviation (design target:
// 1e-9 relative; the offset is removed before integration, so only the rounding of the
// offset samples themselves, ~1e4 * 2^-53 = 1e-12 of the noise, can leak in).
TEST_P(EveryEstimator, ConstantRateOffsetDoesNotChangeResults) {
  const Estimator e = GetParam();
  const auto rate = noise(100000, 12, 1.0);
  auto offset_rate = rate;
  for (auto& v : offset_rate) v += 1e4;
  const double tau0 = 0.005;
  const auto phase = phase_of(rate, tau0);
  const auto factors = averaging_factors(TauGrid{}, 1 / tau0, max_averaging_factor(e, phase.size()));
  const auto plain = devs(e, phase, tau0, factors);
  const auto offset = devs(e, phase_of(offset_rate, tau0), tau0, factors);
  for (std::size_t i = 0; i < plain.size(); ++i) {
    EXPECT_NEAR(offset[i] / plain[i], 1.0, 1e-9) << estimator_name(e) << " m=" << factors[i];
  }
}

// Work is split into fixed chunks whose partial sums are reduced in a fixed order, so the
// thread count cannot change a single bit.
TEST_P(EveryEstimator, ThreadCountDoesNotChangeResults) {
  const Estimator e = GetParam();
  const auto phase = phase_of(noise(300000, 13, 1.0), 1.0);
  const auto factors = averaging_factors(parse_tau_grid("perdecade:7"), 1.0,
                                         max_averaging_factor(e, phase.size()));
  EXPECT_EQ(devs(e, phase, 1.0, factors, 1), devs(e, phase, 1.0, factors, 2));
  EXPECT_EQ(devs(e, phase, 1.0, factors, 1), devs(e, phase, 1.0, factors, 5));
}

INSTANTIATE_TEST_SUITE_P(Core, EveryEstimator,
                         ::testing::Values(Estimator::adev, Estimator::oadev, Estimator::mdev,
                                           Estimator::tdev, Estimator::hdev, Estimator::ohdev),
                         [](const auto& param_info) { return std::string(estimator_name(param_info.param)); });

// Closed form: rate samples y_i = R * i * tau0 (a rate ramp) integrate to x_k = R tau0^2
// k(k-1)/2, whose second difference at lag m is R tau0^2 m^2 everywhere, so the Allan and
// modified Allan deviations are exactly R tau / sqrt(2) (IEEE 952 Annex C) and the Hadamard
// deviations, built on third differences, are exactly 0.
TEST(ClosedForm, RateRampGivesRtauOverSqrt2AndNoHadamard) {
  const double ramp = 3e-3;  // unit/s^2
  const double tau0 = 0.01;
  std::vector<double> rate(5000);
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] = ramp * static_cast<double>(i) * tau0;
  const auto phase = phase_of(rate, tau0);
  const std::vector<std::size_t> factors{1, 3, 10, 100, 1000};
  for (const Estimator e : {Estimator::adev, Estimator::oadev, Estimator::mdev}) {
    for (const auto& p : compute_deviation(e, phase, tau0, factors)) {
      EXPECT_NEAR(p.dev / (ramp * p.tau_s / std::sqrt(2.0)), 1.0, 1e-9)
          << estimator_name(e) << " m=" << p.m;
    }
  }
  for (const Estimator e : {Estimator::hdev, Estimator::ohdev}) {
    for (const auto& p : compute_deviation(e, phase, tau0, factors)) {
      EXPECT_LT(p.dev, 1e-9 * ramp * p.tau_s) << estimator_name(e) << " m=" << p.m;
    }
  }
}

// Closed form: alternating rate +a, -a (a square wave at the Nyquist frequency). At m = 1 the
// second difference of phase is +-2 a tau0, so sigma = sqrt(2) a; at even m the window
// averages are zero and every deviation vanishes.
TEST(ClosedForm, NyquistSquareWave) {
  std::vector<double> rate(1000);
  for (std::size_t i = 0; i < rate.size(); ++i) rate[i] = (i % 2 == 0) ? 1.5 : -1.5;
  const auto phase = phase_of(rate, 0.5);
  const std::vector<std::size_t> one{1};
  EXPECT_NEAR(compute_deviation(Estimator::oadev, phase, 0.5, one)[0].dev, std::sqrt(2.0) * 1.5,
              1e-12);
  const std::vector<std::size_t> even{2, 4, 64};
  for (const auto& p : compute_deviation(Estimator::oadev, phase, 0.5, even)) {
    EXPECT_LT(p.dev, 1e-12);
  }
}

// Stable32's term counts on PHASE.DAT (1001 points): oadev m=128 n=745, mdev m=2 n=996,
// hdev m=2 n=498 (references in docs/validation.md).
TEST(Domain, TermCountsMatchStable32) {
  EXPECT_EQ(term_count(Estimator::oadev, 1001, 128), 745u);
  EXPECT_EQ(term_count(Estimator::mdev, 1001, 2), 996u);
  EXPECT_EQ(term_count(Estimator::hdev, 1001, 2), 498u);
  EXPECT_EQ(term_count(Estimator::oadev, 1001, 1), 999u);
}

TEST(Domain, LargestFactorHasOneTermAndNextHasNone) {
  for (const Estimator e : all_estimators()) {
    for (std::size_t n_phase : {3u, 4u, 10u, 1001u, 1002u, 1003u}) {
      const std::size_t max_m = max_averaging_factor(e, n_phase);
      if (max_m == 0) {  // too short even for m = 1 (Hadamard needs 4 points)
        EXPECT_EQ(term_count(e, n_phase, 1), 0u) << estimator_name(e) << " " << n_phase;
        continue;
      }
      EXPECT_GE(term_count(e, n_phase, max_m), 1u) << estimator_name(e) << " " << n_phase;
      EXPECT_EQ(term_count(e, n_phase, max_m + 1), 0u) << estimator_name(e) << " " << n_phase;
    }
  }
}

TEST(Domain, FactorOutsideDomainIsAnError) {
  const std::vector<double> phase(10, 0.0);
  const std::vector<std::size_t> too_long{5};
  EXPECT_THROW(compute_deviation(Estimator::oadev, phase, 1.0, too_long), InputError);
  const std::vector<std::size_t> zero{0};
  EXPECT_THROW(compute_deviation(Estimator::oadev, phase, 1.0, zero), InputError);
  const std::vector<std::size_t> ok{4};
  EXPECT_THROW(compute_deviation(Estimator::oadev, phase, 0.0, ok), InputError);
}

TEST(Phase, IntegratorInChunksEqualsOnePass) {
  const auto rate = noise(10007, 14, 2.0);
  const auto whole = phase_from_rate(rate, 0.25, 0.1);
  PhaseIntegrator integrator(0.25, 0.1);
  std::vector<double> pieces;
  for (std::size_t begin = 0; begin < rate.size(); begin += 1000) {
    const std::size_t len = std::min<std::size_t>(1000, rate.size() - begin);
    integrator.push(std::span(rate).subspan(begin, len), pieces);
  }
  EXPECT_EQ(pieces, whole);
}

// The integral against a compensated long-double running sum (64-bit mantissa: 2^11 times
// finer than a double), on a record whose offset is not removed (a 1e3 rad/s bias under unit noise), so the
// total grows to 1e9 and every addition rounds. The bound is the header's: a few ulp of the
// value plus a few ulp of a sum of eight samples. Pieces of 999 (not a multiple of the eight
// samples per step) stay within the same bound.
TEST(Phase, IntegralIsWithinAFewUlpOfALongDoubleSum) {
  auto rate = noise(1000003, 15, 1.0);
  for (auto& r : rate) r += 1e3;
  const double tau0 = 0.005;
  const auto phase = phase_from_rate(rate, tau0, 0.0);
  PhaseIntegrator integrator(tau0, 0.0);
  std::vector<double> pieces;
  for (std::size_t begin = 0; begin < rate.size(); begin += 999) {
    integrator.push(std::span(rate).subspan(begin, std::min<std::size_t>(999, rate.size() - begin)), pieces);
  }
  ASSERT_EQ(phase.size(), rate.size() + 1);
  ASSERT_EQ(pieces.size(), phase.size());
  long double exact = 0.0L;  // Kahan-compensated in long double: its own error is ~1e-19 relative
  long double carried = 0.0L;
  double worst = 0.0;
  double worst_pieces = 0.0;
  for (std::size_t k = 1; k < phase.size(); ++k) {
    const long double y = static_cast<long double>(rate[k - 1]) - carried;
    const long double t = exact + y;
    carried = (t - exact) - y;
    exact = t;
    const double value = static_cast<double>(exact * static_cast<long double>(tau0));
    const double bound = 4.0 * std::numeric_limits<double>::epsilon() * (std::abs(value) + 8.0 * 1.1e3 * tau0);
    worst = std::max(worst, std::abs(phase[k] - value) / bound);
    worst_pieces = std::max(worst_pieces, std::abs(pieces[k] - value) / bound);
  }
  EXPECT_LE(worst, 1.0);
  EXPECT_LE(worst_pieces, 1.0);
}

}  // namespace
}  // namespace imunoise
