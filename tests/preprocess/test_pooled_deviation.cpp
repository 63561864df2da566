// Pooled deviations of split records (preprocess/pooled_deviation.hpp): for every estimator of
// the Allan family the pooled value equals a direct sum over the terms that lie inside one
// segment (to 1e-12), a 5 s gap in a 6 h record split at the gap agrees with the gap-free record
// within its intervals, the non-poolable estimators are refused with the reason, and the fit of
// a split record recovers the gap-free record's N and K within their intervals.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/preprocess/pooled_deviation.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "preprocess/preprocess_support.hpp"

namespace imunoise::preprocess {
namespace {

const Estimator kPoolable[] = {Estimator::adev, Estimator::oadev, Estimator::mdev,
                               Estimator::tdev, Estimator::hdev, Estimator::ohdev};

using test::white;

// The definition, written out: sum of squared terms and their count on one segment's angle
// samples x (plain running sum of the rates from 0), for estimator e at factor m.
struct Sums {
  long double s = 0.0L;
  std::size_t n = 0;
};
Sums direct_sums(Estimator e, const std::vector<long double>& x, std::size_t m) {
  Sums out;
  const std::size_t len = x.size();
  auto d2 = [&](std::size_t k) { return x[k + 2 * m] - 2 * x[k + m] + x[k]; };
  auto d3 = [&](std::size_t k) { return x[k + 3 * m] - 3 * x[k + 2 * m] + 3 * x[k + m] - x[k]; };
  switch (e) {
    case Estimator::oadev:
      for (std::size_t k = 0; k + 2 * m < len; ++k) { out.s += d2(k) * d2(k); ++out.n; }
      break;
    case Estimator::adev:
      for (std::size_t k = 0; k + 2 * m < len; k += m) { out.s += d2(k) * d2(k); ++out.n; }
      break;
    case Estimator::mdev:
    case Estimator::tdev:
      for (std::size_t j = 0; j + 3 * m <= len; ++j) {
        long double inner = 0.0L;
        for (std::size_t i = j; i < j + m; ++i) inner += d2(i);
        out.s += inner * inner;
        ++out.n;
      }
      break;
    case Estimator::ohdev:
      for (std::size_t k = 0; k + 3 * m < len; ++k) { out.s += d3(k) * d3(k); ++out.n; }
      break;
    case Estimator::hdev:
      for (std::size_t k = 0; k + 3 * m < len; k += m) { out.s += d3(k) * d3(k); ++out.n; }
      break;
    default:
      break;
  }
  return out;
}

// The variance from the pooled sums: S / (c n) with each estimator's constant c.
double direct_dev(Estimator e, long double s, std::size_t n, std::size_t m, double tau0) {
  const long double tau = static_cast<long double>(m) * tau0;
  long double var = 0.0L;
  switch (e) {
    case Estimator::adev:
    case Estimator::oadev: var = s / (2 * tau * tau * n); break;
    case Estimator::mdev: var = s / (2.0L * m * m * tau * tau * n); break;
    case Estimator::tdev: var = tau * tau / 3 * s / (2.0L * m * m * tau * tau * n); break;
    case Estimator::hdev:
    case Estimator::ohdev: var = s / (6 * tau * tau * n); break;
    default: break;
  }
  return static_cast<double>(std::sqrt(var));
}

TEST(PooledDeviation, EqualsTheDirectSumOverTheSegmentsTermsForEveryEstimator) {
  const double tau0 = 0.01;
  auto v = white(3000, 0.02, 31);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] += 0.5 + 1e-4 * static_cast<double>(i);  // offset and ramp
  // Three segments of unequal length (a gap break, a rejected sample) and one too short for m >= 4.
  const std::vector<std::size_t> breaks = {1200, 2980};
  const std::vector<std::size_t> removed = {2100};
  const auto segments = split_segments(v.size(), breaks, removed);
  ASSERT_EQ(segments.size(), 4u);
  const std::vector<std::size_t> factors = {1, 2, 3, 5, 8, 13, 40, 100, 300};
  for (const Estimator e : kPoolable) {
    SCOPED_TRACE(std::string(estimator_name(e)));
    PoolOptions options;
    options.no_ci = true;
    const auto pooled = pooled_deviation(e, v, segments, tau0, factors, options);
    ASSERT_EQ(pooled.points.size(), factors.size());
    for (const auto& p : pooled.points) {
      long double s = 0.0L;
      std::size_t n = 0;
      for (const auto& seg : segments) {
        std::vector<long double> x(seg.size() + 1, 0.0L);
        for (std::size_t i = 0; i < seg.size(); ++i) x[i + 1] = x[i] + static_cast<long double>(v[seg.begin + i]) * tau0;
        const Sums d = direct_sums(e, x, p.m);
        s += d.s;
        n += d.n;
      }
      ASSERT_GT(n, 0u);
      EXPECT_EQ(p.n, n) << "m = " << p.m;
      EXPECT_NEAR(p.dev / direct_dev(e, s, n, p.m, tau0), 1.0, 1e-12) << "m = " << p.m;
    }
  }
}

TEST(PooledDeviation, OneSegmentIsTheOneRecordEstimatorWithItsIntervals) {
  const double tau0 = 0.01;
  const auto v = white(20'000, 1.0, 32);
  const std::vector<Segment> one = {{0, v.size()}};
  const auto phase = phase_from_rate(v, tau0, compensated_mean(v));
  const std::vector<std::size_t> factors = {1, 4, 16, 64, 256};
  for (const Estimator e : kPoolable) {
    SCOPED_TRACE(std::string(estimator_name(e)));
    auto full = compute_deviation(e, phase, tau0, factors);
    fill_confidence(full, e, phase, 0.683);
    const auto pooled = pooled_deviation(e, v, one, tau0, factors);
    ASSERT_EQ(pooled.points.size(), full.size());
    for (std::size_t j = 0; j < full.size(); ++j) {
      EXPECT_NEAR(pooled.points[j].dev / full[j].dev, 1.0, 1e-12);
      EXPECT_EQ(pooled.points[j].alpha, full[j].alpha);
      EXPECT_NEAR(pooled.points[j].edf / full[j].edf, 1.0, 1e-12);
      EXPECT_NEAR(pooled.points[j].ci_high / full[j].ci_high, 1.0, 1e-12);
    }
  }
}

TEST(PooledDeviation, SatterthwaiteEdfOfTwoEqualHalvesIsTheirSum) {
  const double tau0 = 0.01;
  const auto v = white(20'000, 1.0, 33);
  const std::vector<Segment> halves = {{0, 10'000}, {10'000, 20'000}};
  PoolOptions options;
  options.forced_alpha = 0;
  const std::vector<std::size_t> factors = {1, 10, 100};
  const auto pooled = pooled_deviation(Estimator::oadev, v, halves, tau0, factors, options);
  for (const auto& p : pooled.points) {
    // Equal halves have equal term counts and EDFs: 1 / sum (1/2)^2 / e = 2 e.
    const double e = greenhall_riley_edf(0, *difference_variance(Estimator::oadev), p.m, 10'001);
    EXPECT_NEAR(p.edf / (2 * e), 1.0, 1e-12) << "m = " << p.m;
    const auto ci = chi2_interval(p.dev, p.edf, 0.683);
    EXPECT_EQ(p.ci_low, ci.low);
  }
}

TEST(PooledDeviation, NonPoolableEstimatorsAreRefusedWithTheReason) {
  const auto v = white(1000, 1.0, 34);
  const std::vector<Segment> two = {{0, 500}, {500, 1000}};
  const std::vector<std::size_t> factors = {1, 2};
  for (const Estimator e : kPoolable) EXPECT_TRUE(pooling_refusal(e).empty());
  for (const Estimator e : {Estimator::totdev, Estimator::mtotdev, Estimator::ttotdev, Estimator::htotdev,
                            Estimator::theo1, Estimator::theobr, Estimator::mtie, Estimator::tierms}) {
    SCOPED_TRACE(std::string(estimator_name(e)));
    EXPECT_FALSE(pooling_refusal(e).empty());
    try {
      pooled_deviation(e, v, two, 0.01, factors);
      ADD_FAILURE() << "not refused";
    } catch (const InputError& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find(std::string(estimator_name(e)) + " cannot be pooled"), std::string::npos) << what;
      EXPECT_NE(what.find("fix: use adev, oadev"), std::string::npos) << what;
    }
  }
  const std::vector<Segment> outside = {{0, 1001}};
  EXPECT_THROW(pooled_deviation(Estimator::oadev, v, outside, 0.01, factors), InputError);
}

// 6 h at 200 Hz of white rate noise plus a rate random walk; 5 s (1000 samples) taken out at the
// middle and the rest split there. Every estimator's pooled curve must lie inside the 95 %
// interval of the gap-free record's curve (the two share all but 0.02 % of the samples, so any
// difference beyond rounding comes from the terms lost at the gap and at the segment ends).
class GapSplit : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::size_t n = 6 * 3600 * 200;
    v_ = white(n, 1e-3, 3);
    std::mt19937_64 rng(4);
    std::normal_distribution<double> g(0.0, 2e-7);
    double walk = 0.0;
    for (auto& x : v_) { walk += g(rng); x += walk; }
    const std::size_t gap_at = n / 2;
    cut_.assign(v_.begin(), v_.begin() + static_cast<std::ptrdiff_t>(gap_at));
    cut_.insert(cut_.end(), v_.begin() + static_cast<std::ptrdiff_t>(gap_at + 1000), v_.end());
    const std::vector<std::size_t> breaks = {gap_at};
    segments_ = split_segments(cut_.size(), breaks);
  }
  static std::vector<double> v_;
  static std::vector<double> cut_;
  static std::vector<Segment> segments_;
};
std::vector<double> GapSplit::v_;
std::vector<double> GapSplit::cut_;
std::vector<Segment> GapSplit::segments_;

TEST_F(GapSplit, FiveSecondGapInSixHoursAgreesWithTheGapFreeRecordForEveryEstimator) {
  const double tau0 = 1.0 / 200.0;
  ASSERT_EQ(segments_.size(), 2u);
  const auto phase = phase_from_rate(v_, tau0, compensated_mean(v_));
  for (const Estimator e : kPoolable) {
    SCOPED_TRACE(std::string(estimator_name(e)));
    // Up to half the longest factor a segment allows: at the segment's last octave its few
    // terms (EDF ~ 2) and the gap-free record's many are nearly independent estimates, which
    // need not lie in each other's 95 % interval (measured: oadev at m = 2^20 of a 6 h, 200 Hz
    // record, 2.5e-5 split vs 5.9e-5 gap-free, the gap-free value inside the split's
    // interval, not the converse).
    std::vector<std::size_t> factors;
    for (std::size_t m = 1; m <= max_averaging_factor(e, cut_.size() / 2) / 2; m *= 4) factors.push_back(m);
    auto full = compute_deviation(e, phase, tau0, factors);
    fill_confidence(full, e, phase, 0.95);
    PoolOptions options;
    options.level = 0.95;
    const auto pooled = pooled_deviation(e, cut_, segments_, tau0, factors, options);
    ASSERT_EQ(pooled.points.size(), full.size());
    for (std::size_t j = 0; j < full.size(); ++j) {
      SCOPED_TRACE("m = " + std::to_string(full[j].m));
      const auto& p = pooled.points[j];
      EXPECT_GE(p.dev, full[j].ci_low);
      EXPECT_LE(p.dev, full[j].ci_high);
      EXPECT_LT(p.n, full[j].n);  // the terms spanning the gap are gone
      // The split record's own interval contains the gap-free estimate too; for the same noise
      // type its EDF is at most the gap-free EDF (+1 %): fewer terms. (A different type may be
      // identified on half the record at the long taus, and then its EDF may be larger.)
      EXPECT_GE(full[j].dev, p.ci_low);
      EXPECT_LE(full[j].dev, p.ci_high);
      if (p.alpha == full[j].alpha) {
        EXPECT_LE(p.edf, 1.01 * full[j].edf);
      }
      EXPECT_GT(p.edf, 0.0);
    }
  }
}

TEST_F(GapSplit, FitOfTheSplitRecordRecoversTheGapFreeNoiseTerms) {
  const double rate = 200.0;
  study::Record whole;
  whole.source = "whole";
  whole.rate_hz = rate;
  whole.n_samples = v_.size();
  whole.phase_si = phase_from_rate(v_, 1.0 / rate, compensated_mean(v_));
  whole.rate_unit = parse_unit("rad/s");
  whole.unit_given = true;
  study::Record split = whole;
  split.source = "split";
  split.n_samples = cut_.size();
  split.phase_si = phase_from_rate(cut_, 1.0 / rate, compensated_mean(cut_));
  split.segments = segments_;
  split.rate_si = cut_;
  fit::FitOptions options;
  const auto a = study::fit_channel(whole, options);
  const auto b = study::fit_channel(split, options);
  // White rate noise 1e-3 rad/s at 200 Hz: N = 1e-3 / sqrt(200); random walk 2e-7 per sample: K = 2e-7 sqrt(200).
  const double n_true = 1e-3 / std::sqrt(rate);
  const double k_true = 2e-7 * std::sqrt(rate);
  for (const auto* r : {&a, &b}) {
    EXPECT_LE(r->coefficients.random_walk.ci_low, n_true);
    EXPECT_GE(r->coefficients.random_walk.ci_high, n_true);
    EXPECT_LE(r->coefficients.rate_random_walk.ci_low, k_true);
    EXPECT_GE(r->coefficients.rate_random_walk.ci_high, k_true);
  }
  // The split fit's estimates inside the gap-free fit's intervals, and the split is said.
  EXPECT_GE(b.coefficients.random_walk.value, a.coefficients.random_walk.ci_low);
  EXPECT_LE(b.coefficients.random_walk.value, a.coefficients.random_walk.ci_high);
  EXPECT_GE(b.coefficients.rate_random_walk.value, a.coefficients.rate_random_walk.ci_low);
  EXPECT_LE(b.coefficients.rate_random_walk.value, a.coefficients.rate_random_walk.ci_high);
  bool said = false;
  for (const auto& w : b.summary.warnings) said = said || w.find("pooled over 2 segments") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace imunoise::preprocess
