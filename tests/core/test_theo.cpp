// Theo1: Stable32's PHASE.DAT value, the tau/m conventions, and the vectorized algorithm against
// the literal double sum (reference_total.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/nbs14.hpp"
#include "core/offset_random_walk.hpp"
#include "core/reference_total.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"

namespace imunoise {
namespace {

TEST(Theo1, Stable32PhaseDat) {
  const auto y = test::nbs14_1000_point_frequency();
  const auto x = phase_from_rate(y, 1.0, compensated_mean(y));
  const std::size_t m[1] = {10};
  const auto p = theo1(x, 1.0, m);
  EXPECT_NEAR(p[0].dev, 1.0757e-01, 0.00005e-01 + 1e-9);
  EXPECT_DOUBLE_EQ(p[0].tau_s, 7.5);
  EXPECT_EQ(p[0].n, 4955u);
}

// Stable32's bias-corrected Theo1 row on PHASE.DAT is ThêoBR with its N/6 - 3 ratios.
TEST(TheoBr, Stable32PhaseDat) {
  const auto y = test::nbs14_1000_point_frequency();
  const auto x = phase_from_rate(y, 1.0, compensated_mean(y));
  const std::size_t m[1] = {10};
  TheoBiasFactor kf;
  const auto p = theobr(x, 1.0, m, {}, TheoBrRatios::stable32, &kf);
  EXPECT_NEAR(p[0].dev, 8.3520e-02, 0.00005e-02 + 1e-9);
  EXPECT_EQ(kf.ratios, 164u);  // i = 0..floor(1001/6) - 3
  EXPECT_DOUBLE_EQ(p[0].tau_s, 7.5);
  EXPECT_EQ(p[0].n, 4955u);
}

// kf against the literal definition: long-double Avar and Theo1 sums per ratio, on random-walk
// phase with a large offset; ThêoBR is theo1 times sqrt(kf) at every m.
TEST(TheoBr, BiasFactorEqualsDefinition) {
  const auto x = test::offset_random_walk(400, 5, 5e6, -1e3);
  for (const auto rule : {TheoBrRatios::taylor_howe, TheoBrRatios::stable32}) {
    const std::size_t n = rule == TheoBrRatios::stable32 ? x.size() / 6 - 3 : x.size() / 30 - 3;
    long double sum = 0.0L;
    std::size_t count = 0;
    for (std::size_t i = 0; i <= n && 9 + 3 * i <= (x.size() - 1) / 2; ++i, ++count) {
      const std::size_t ma = 9 + 3 * i;
      long double avar = 0.0L;
      for (std::size_t k = 0; k + 2 * ma < x.size(); ++k) {
        const long double d = static_cast<long double>(x[k + 2 * ma]) - 2.0L * x[k + ma] + x[k];
        avar += d * d;
      }
      avar /= 2.0L * ma * ma * static_cast<long double>(x.size() - 2 * ma);
      const double theo = test::reference_theo1(x, 1.0, 12 + 4 * i);
      sum += avar / (static_cast<long double>(theo) * theo);
    }
    const double expected = static_cast<double>(sum / count);
    const TheoBiasFactor kf = theobr_bias_factor(x, 1.0, {}, rule);
    EXPECT_EQ(kf.ratios, count);
    EXPECT_NEAR(kf.avar_over_theo1, expected, 1e-10 * expected);
    const std::size_t m[3] = {2, 40, 398};
    const auto br = theobr(x, 1.0, m, {}, rule);
    const auto t1 = theo1(x, 1.0, m);
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_NEAR(br[j].dev, t1[j].dev * std::sqrt(kf.avar_over_theo1), 1e-15 * br[j].dev);
    }
  }
}

TEST(TheoBr, DomainAndErrors) {
  EXPECT_EQ(max_averaging_factor(Estimator::theobr, 89), 0u);
  EXPECT_EQ(max_averaging_factor(Estimator::theobr, 90), 88u);
  EXPECT_TRUE(requires_even_factor(Estimator::theobr));
  EXPECT_DOUBLE_EQ(tau_per_factor(Estimator::theobr), 0.75);
  const std::vector<double> x(60, 1.0);
  EXPECT_THROW(theobr_bias_factor(x, 1.0), InputError);
  const std::vector<double> flat(200, 3.0);  // Theo1 = 0: no ratio exists
  EXPECT_THROW(theobr_bias_factor(flat, 1.0), InputError);
  EXPECT_THROW(parse_theobr_ratios("stable"), InputError);
  EXPECT_EQ(parse_theobr_ratios("stable32"), TheoBrRatios::stable32);
}

TEST(Theo1, FastEqualsDefinitionWithLargeOffset) {
  const auto x = test::offset_random_walk(500, 3, -3e7, 2e4, 1.0);
  for (std::size_t m = 2; m < x.size(); m += (m < 20 ? 2 : 38)) {
    const std::size_t f[1] = {m};
    const double ref = test::reference_theo1(x, 0.01, m);
    EXPECT_NEAR(theo1(x, 0.01, f)[0].dev, ref, 1e-10 * ref) << "m=" << m;
  }
}

TEST(Theo1, EvenFactorsOnlyAndGrids) {
  const std::vector<double> x(101, 0.0);
  const std::size_t odd[1] = {3};
  EXPECT_THROW(theo1(x, 1.0, odd), InputError);
  EXPECT_EQ(max_averaging_factor(Estimator::theo1, 101), 100u);
  EXPECT_EQ(max_averaging_factor(Estimator::theo1, 100), 98u);
  const auto octave = estimator_averaging_factors(Estimator::theo1, parse_tau_grid("octave"), 1.0, 101);
  EXPECT_EQ(octave, (std::vector<std::size_t>{2, 4, 8, 16, 32, 64}));
  const auto decade = estimator_averaging_factors(Estimator::theo1, parse_tau_grid("decade"), 1.0, 101);
  EXPECT_EQ(decade, (std::vector<std::size_t>{2, 4, 10, 20, 40, 100}));
  const auto taus = estimator_averaging_factors(Estimator::theo1, parse_tau_grid("7.5,1.5"), 1.0, 101);
  EXPECT_EQ(taus, (std::vector<std::size_t>{2, 10}));
  EXPECT_THROW(estimator_averaging_factors(Estimator::theo1, parse_tau_grid("2"), 1.0, 101),
               InputError);
  // Other estimators keep the ordinary grid.
  EXPECT_EQ(estimator_averaging_factors(Estimator::oadev, parse_tau_grid("octave"), 1.0, 9),
            (std::vector<std::size_t>{1, 2, 4}));
}

TEST(Theo1, ThreadCountDoesNotChangeResults) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(5000);
  for (auto& v : x) v = g(rng);
  const std::size_t f[2] = {64, 1024};
  const auto a = theo1(x, 1.0, f, {1});
  const auto b = theo1(x, 1.0, f, {2});
  EXPECT_EQ(a[0].dev, b[0].dev);
  EXPECT_EQ(a[1].dev, b[1].dev);
}

}  // namespace
}  // namespace imunoise
