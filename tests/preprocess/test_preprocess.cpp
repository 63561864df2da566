// Preprocessing: detrend recovers injected drift within its standard error; MAD spikes are
// found exactly; DAVAR flags a warm-up (and suggests a skip that removes it) and a step in
// noise level at the right time, and calls white noise stationary; a 5 s gap in a 6 h record
// analysed as two pooled segments agrees with the gap-free record within its intervals.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "imunoise/allan.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/preprocess/temperature.hpp"
#include "preprocess/preprocess_support.hpp"

namespace imunoise::preprocess {
namespace {

using test::white;

TEST(Detrend, LinearDriftRecoveredWithinItsStandardErrorAndReported) {
  const double rate = 100.0;
  const std::size_t n = 200'000;
  const double sigma = 0.01;
  auto v = white(n, sigma, 1);
  const double bias = 0.3;
  const double slope = 2e-5;  // per second: 0.04 over the record, 4 sigma
  for (std::size_t i = 0; i < n; ++i) v[i] += bias + slope * static_cast<double>(i) / rate;
  const DetrendReport r = detrend(v, rate, DetrendOrder::linear);
  ASSERT_EQ(r.coefficients.size(), 2u);
  // Standard error of an OLS slope over equally spaced t: sigma / sqrt(sum (t - mean)^2).
  const double duration = static_cast<double>(n) / rate;
  const double se_slope = sigma / std::sqrt(static_cast<double>(n) * duration * duration / 12.0);
  EXPECT_NEAR(r.coefficients[1], slope, 5 * se_slope);
  EXPECT_NEAR(r.coefficients[0], bias, 5 * sigma * 2 / std::sqrt(static_cast<double>(n)));
  // RMS of a line over the record about its mean: slope * duration / sqrt(12).
  EXPECT_NEAR(r.removed_rms, slope * duration / std::sqrt(12.0), 5 * se_slope * duration);
  // What is left is the white noise: its mean is zero and its spread sigma.
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(n);
  EXPECT_NEAR(mean, 0.0, 1e-12);
}

TEST(Detrend, QuadraticCoefficientsInPowersOfTime) {
  const double rate = 50.0;
  const std::size_t n = 50'001;
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / rate;
    v[i] = 1.5 - 3e-3 * t + 4e-6 * t * t;
  }
  const DetrendReport r = detrend(v, rate, DetrendOrder::quadratic);
  EXPECT_NEAR(r.coefficients[0], 1.5, 1e-9);
  EXPECT_NEAR(r.coefficients[1], -3e-3, 1e-12);
  EXPECT_NEAR(r.coefficients[2], 4e-6, 1e-15);
  for (double x : v) ASSERT_NEAR(x, 0.0, 1e-9);
  EXPECT_THROW(parse_detrend("cubic"), InputError);
}

TEST(Spikes, InjectedSpikesFoundExactlyAndCleanRecordsPass) {
  auto v = white(100'000, 1.0, 2);
  EXPECT_TRUE(find_spikes(v, 0.0, "clean").indices.empty());
  const std::vector<std::size_t> where = {17, 5000, 5001, 77'777, 99'999};
  for (const auto i : where) v[i] += (i % 2 ? -25.0 : 25.0);
  const OutlierReport r = find_spikes(v, 0.0, "spiky");
  EXPECT_EQ(r.indices, where);
  EXPECT_NEAR(r.robust_sigma, 1.0, 0.02);  // MAD-based sigma: sd ~ 1.17 / sqrt(n) relative
  const double z = default_spike_threshold(4'320'000);  // 4.32e6 * P(|Z| > z) = 0.01
  EXPECT_NEAR(4.32e6 * std::erfc(z / std::sqrt(2.0)), 0.01, 1e-9);
  EXPECT_NEAR(z, 5.97, 0.01);
  std::vector<double> stuck(1000, 3.0);
  stuck[3] = 4.0;
  EXPECT_THROW(find_spikes(stuck, 0.0, "stuck"), InputError);
}

TEST(Segments, SplitAtBreaksAndDroppedSamples) {
  const std::vector<std::size_t> breaks = {10, 50};
  const std::vector<std::size_t> removed = {20, 21, 99};
  const auto s = split_segments(100, breaks, removed);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].begin, 0u); EXPECT_EQ(s[0].end, 10u);
  EXPECT_EQ(s[1].begin, 10u); EXPECT_EQ(s[1].end, 20u);
  EXPECT_EQ(s[2].begin, 22u); EXPECT_EQ(s[2].end, 50u);
  EXPECT_EQ(s[3].begin, 50u); EXPECT_EQ(s[3].end, 99u);
}

TEST(GapsSplit, FiveSecondGapInSixHoursAgreesWithTheGapFreeRecord) {
  const double rate = 200.0;
  const std::size_t n = 6 * 3600 * 200;  // 4.32 M samples
  const double tau0 = 1.0 / rate;
  // White rate noise plus a rate random walk (so the long taus carry K as well).
  auto v = white(n, 1e-3, 3);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0.0, 2e-7);
  double walk = 0.0;
  for (auto& x : v) { walk += g(rng); x += walk; }
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= n / 10; m *= 4) factors.push_back(m);
  const auto phase = phase_from_rate(v, tau0, compensated_mean(v));
  const auto full = oadev(phase, tau0, factors);
  // The same record with 5 s (1000 samples) missing in the middle, split at the gap.
  const std::size_t gap_at = n / 2;
  std::vector<double> cut(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(gap_at));
  cut.insert(cut.end(), v.begin() + static_cast<std::ptrdiff_t>(gap_at + 1000), v.end());
  const std::vector<std::size_t> breaks = {gap_at};
  const auto segments = split_segments(cut.size(), breaks);
  ASSERT_EQ(segments.size(), 2u);
  const auto pooled = pooled_oadev(cut, segments, tau0, factors);
  ASSERT_EQ(pooled.size(), full.size());
  for (std::size_t j = 0; j < full.size(); ++j) {
    SCOPED_TRACE("m = " + std::to_string(full[j].m));
    const double edf = static_cast<double>(n + 1) / static_cast<double>(full[j].m) - 1.0;
    const auto ci = chi2_interval(full[j].dev, edf, 0.95);
    EXPECT_GE(pooled[j].dev, ci.low);
    EXPECT_LE(pooled[j].dev, ci.high);
    EXPECT_LT(pooled[j].n, full[j].n);  // the terms spanning the gap are gone
  }
  // A single segment pools to the one-record estimator (to rounding).
  const std::vector<Segment> one = {{0, n}};
  const auto same = pooled_oadev(v, one, tau0, factors);
  for (std::size_t j = 0; j < full.size(); ++j) EXPECT_NEAR(same[j].dev / full[j].dev, 1.0, 1e-12);
}

TEST(Davar, WhiteNoiseIsStationary) {
  const auto v = white(120'000, 1.0, 5);
  const DavarResult r = dynamic_allan(v, 100.0, {60.0, 30.0});
  EXPECT_TRUE(r.stationary);
  EXPECT_EQ(r.suggested_skip_s, 0.0);
  EXPECT_EQ(r.window_start_s.size(), r.avar.size());
  EXPECT_TRUE(r.change_times_s.empty());
}

TEST(Davar, StepInNoiseLevelFlaggedAtTheRightTime) {
  const double rate = 100.0;
  auto v = white(120'000, 1.0, 6);  // 1200 s
  const double step_at_s = 400.0;
  for (std::size_t i = static_cast<std::size_t>(step_at_s * rate); i < v.size(); ++i) v[i] *= 1.5;
  const DavarResult r = dynamic_allan(v, rate, {60.0, 10.0});
  EXPECT_FALSE(r.stationary);
  ASSERT_EQ(r.change_times_s.size(), 1u);
  EXPECT_NEAR(r.change_times_s[0], step_at_s, r.window_s / 2);
}

TEST(Davar, ExponentialWarmUpFlaggedAndTheSuggestedSkipRemovesIt) {
  const double rate = 100.0;
  auto v = white(180'000, 1.0, 7);  // 1800 s
  const double time_constant = 60.0;
  // A warm-up: the noise starts 4x larger and settles exponentially, with a decaying bias.
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double t = static_cast<double>(i) / rate;
    const double e = std::exp(-t / time_constant);
    v[i] = v[i] * (1.0 + 3.0 * e) + 20.0 * e;
  }
  const DavarResult r = dynamic_allan(v, rate, {60.0, 15.0});
  EXPECT_FALSE(r.stationary);
  EXPECT_GT(r.suggested_skip_s, time_constant);
  EXPECT_LT(r.suggested_skip_s, 10 * time_constant);
  const auto skip = static_cast<std::size_t>(r.suggested_skip_s * rate);
  const std::vector<double> rest(v.begin() + static_cast<std::ptrdiff_t>(skip), v.end());
  const DavarResult after = dynamic_allan(rest, rate, {60.0, 15.0});
  EXPECT_TRUE(after.stationary) << "skip " << r.suggested_skip_s << " s";
}

}  // namespace
}  // namespace imunoise::preprocess

namespace imunoise::preprocess {
namespace {

TEST(TemperatureBins, BiasAndRandomWalkPerBinRecovered) {
  // 100 Hz; the temperature ramps 10 -> 40 degC and back twice; bias 1e-3 + 2e-4 (T - 25) and a
  // white-noise level that doubles above 30 degC. Bins of 10 degC: [10,20) [20,30) [30,40).
  const double rate = 100.0;
  const std::size_t n = 400'000;
  std::mt19937_64 rng(21);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> temperature(n);
  std::vector<double> values(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double phase = std::fmod(static_cast<double>(i) / (n / 2.0), 1.0);  // two cycles
    const double t_c = 10.0 + 30.0 * (phase < 0.5 ? 2 * phase : 2 - 2 * phase);
    temperature[i] = std::min(t_c, 39.999);
    const double sigma = t_c >= 30.0 ? 2e-3 : 1e-3;
    values[i] = 1e-3 + 2e-4 * (t_c - 25.0) + sigma * g(rng);
  }
  const auto bins = temperature_bins(values, temperature, rate, 10.0);
  ASSERT_EQ(bins.size(), 3u);
  for (const auto& b : bins) {
    SCOPED_TRACE("bin " + std::to_string(b.low));
    EXPECT_EQ(b.high - b.low, 10.0);
    // Runs: the middle range is crossed 4 times; the bottom one is left and re-entered at the
    // cycle boundary (3 runs: start, boundary, end); each peak is one run in the top one (2).
    EXPECT_EQ(b.segments, b.low == 10.0 ? 3u : b.low == 20.0 ? 4u : 2u);
    // Bias: the true mean over the bin's samples is 1e-3 + 2e-4 (mean T - 25).
    EXPECT_NEAR(b.bias_si, 1e-3 + 2e-4 * (b.mean_temperature - 25.0), 5 * b.bias_stderr_si);
    // N = sigma / sqrt(rate) for white rate noise; at tau = 1 s the pooled edf is ~ samples/100,
    // relative sd of the deviation 1 / sqrt(2 edf) ~ 3 %: 5 sd = 16 %. The bias ramp inside the
    // bin adds a drift of 2e-4 * 10 over a pass, small at 1 s.
    const double sigma = b.low >= 30.0 ? 2e-3 : 1e-3;
    EXPECT_NEAR(b.random_walk_si / (sigma / std::sqrt(rate)), 1.0, 0.16);
    EXPECT_EQ(b.random_walk_tau_s, 1.28);
  }
  EXPECT_THROW(temperature_bins(values, temperature, rate, 0.0), InputError);
}

}  // namespace
}  // namespace imunoise::preprocess
