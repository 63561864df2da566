// The random streams: published test vectors, an independent check of the jump constants, bit
// patterns from an independent re-implementation (tests/sim/reference/sim_reference.py), and
// distribution tests of the normal transform at fixed seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

#include "imunoise/sim/rng.hpp"

using imunoise::sim::make_stream;
using imunoise::sim::NormalGenerator;
using imunoise::sim::SplitMix64;
using imunoise::sim::Xoshiro256StarStar;

TEST(SplitMix64, PublishedSequence) {
  // First outputs for seed 1234567, as published with the algorithm's reference code.
  SplitMix64 sm(1234567);
  const std::array<std::uint64_t, 5> expected = {6457827717110365317ULL, 3203168211198807973ULL,
                                                 9817491932198370423ULL, 4593380528125082431ULL,
                                                 16408922859458223821ULL};
  for (const auto e : expected) EXPECT_EQ(sm.next(), e);
}

TEST(Xoshiro256StarStar, ReferenceSequenceFromState1234) {
  Xoshiro256StarStar x(Xoshiro256StarStar::State{1, 2, 3, 4});
  const std::array<std::uint64_t, 10> expected = {
      11520ULL, 0ULL, 1509978240ULL, 1215971899390074240ULL, 1216172134540287360ULL,
      607988272756665600ULL, 16172922978634559625ULL, 8476171486693032832ULL,
      10595114339597558777ULL, 2904607092377533576ULL};
  for (const auto e : expected) EXPECT_EQ(x(), e);
}

TEST(Xoshiro256StarStar, JumpsEqualMatrixPowers) {
  // sim_reference.py raises the engine's 256x256 GF(2) transition matrix to 2^128 and 2^192.
  Xoshiro256StarStar x(42);
  EXPECT_EQ(x.state(), (Xoshiro256StarStar::State{0xbdd732262feb6e95ULL, 0x28efe333b266f103ULL,
                                                   0x47526757130f9f52ULL, 0x581ce1ff0e4ae394ULL}));
  Xoshiro256StarStar j = x;
  j.jump();
  EXPECT_EQ(j.state(), (Xoshiro256StarStar::State{0x81746704fde896b5ULL, 0x645e944932dae0aeULL,
                                                   0xf4776829231c282cULL, 0x2393f9798732dba1ULL}));
  Xoshiro256StarStar l = x;
  l.long_jump();
  EXPECT_EQ(l.state(), (Xoshiro256StarStar::State{0x1c5592a8d2450a14ULL, 0xe09b0d035aa06fd9ULL,
                                                   0xac4a2ed7fc28e84cULL, 0xdb0c552285cab3c6ULL}));
  EXPECT_EQ(make_stream(42, 1, 0).state(), l.state());
  EXPECT_EQ(make_stream(42, 0, 1).state(), j.state());
}

TEST(NormalGenerator, BitsMatchIndependentReimplementation) {
  NormalGenerator g(Xoshiro256StarStar(7));
  const std::array<double, 8> first = {0x1.441396c0e0941p+0,  0x1.10328d8dd8802p-2,
                                       -0x1.2a48a63f67448p+0, 0x1.fcc7c6c16eddfp+0,
                                       -0x1.40e3c5a239ba9p+1, 0x1.b298ff1af3b29p+0,
                                       0x1.cd5a8386be265p-4,  -0x1.7181446ed369dp-4};
  for (const double e : first) EXPECT_EQ(g(), e);
  // 200000 variates exercise the wedges (~1.5 %) and the tail (~0.03 %) many times.
  NormalGenerator h(Xoshiro256StarStar(7));
  std::vector<double> v(200000);
  h.fill(v);
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_EQ(v[i], first[i]);
  EXPECT_EQ(v.back(), -0x1.278355838cfbbp-2);
  EXPECT_EQ(h.engine().state(), (Xoshiro256StarStar::State{0x7990d66f538dc871ULL, 0x5dfc0c21deb988d2ULL,
                                                            0xb0fc8c517811816bULL, 0xfab59e917b878b6eULL}));
}

TEST(NormalGenerator, FillEqualsRepeatedCalls) {
  NormalGenerator a(Xoshiro256StarStar(99));
  NormalGenerator b(Xoshiro256StarStar(99));
  std::vector<double> v(10007);
  a.fill(std::span<double>(v).first(3));
  a.fill(std::span<double>(v).subspan(3));
  for (const double x : v) ASSERT_EQ(x, b());
}

// Distribution tests on 2^21 variates at seed 2024. Each check's threshold has probability
// 1e-5 of being exceeded by a correct N(0,1) generator (normal approximations of the sample
// moments, exact chi-squared for the histogram), so a failure means a defect.
TEST(NormalGenerator, DistributionAtFixedSeed) {
  constexpr std::size_t n = std::size_t{1} << 21;
  std::vector<double> v(n);
  NormalGenerator g(Xoshiro256StarStar(2024));
  g.fill(v);
  const double z = 4.4172;  // two-sided 1e-5 normal quantile
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  for (const double x : v) {
    s1 += x;
    s2 += x * x;
    s3 += x * x * x;
    s4 += x * x * x * x;
  }
  const double dn = static_cast<double>(n);
  EXPECT_LT(std::fabs(s1 / dn), z / std::sqrt(dn));
  EXPECT_LT(std::fabs(s2 / dn - 1.0), z * std::sqrt(2.0 / dn));
  EXPECT_LT(std::fabs(s3 / dn), z * std::sqrt(15.0 / dn));         // Var(x^3) = 15
  EXPECT_LT(std::fabs(s4 / dn - 3.0), z * std::sqrt(96.0 / dn));   // Var(x^4) = 105 - 9

  // Histogram on 256 equiprobable cells of N(0,1), chi-squared with 255 degrees of freedom.
  constexpr int cells = 256;
  boost::math::normal unit;
  std::vector<double> edges(cells - 1);
  for (int i = 1; i < cells; ++i) edges[i - 1] = boost::math::quantile(unit, static_cast<double>(i) / cells);
  std::vector<double> counts(cells, 0.0);
  for (const double x : v) {
    counts[static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin())] += 1.0;
  }
  const double expected = dn / cells;
  double chi2 = 0.0;
  for (const double c : counts) chi2 += (c - expected) * (c - expected) / expected;
  const boost::math::chi_squared dist(cells - 1);
  EXPECT_LT(chi2, boost::math::quantile(dist, 1.0 - 1e-5));
  EXPECT_GT(chi2, boost::math::quantile(dist, 1e-5));

  // The tail beyond the ziggurat's base (|x| > r = 3.6542) is sampled by a separate algorithm:
  // its frequency is binomial(n, p), p = 2 (1 - Phi(r)).
  const double r = 3.6541528853610088;
  const double p = 2.0 * boost::math::cdf(boost::math::complement(unit, r));
  double tail = 0.0, deep = 0.0;
  for (const double x : v) {
    tail += std::fabs(x) > r ? 1.0 : 0.0;
    deep += std::fabs(x) > 4.5 ? 1.0 : 0.0;
  }
  EXPECT_LT(std::fabs(tail - dn * p), z * std::sqrt(dn * p * (1 - p)));
  const double p_deep = 2.0 * boost::math::cdf(boost::math::complement(unit, 4.5));
  EXPECT_LT(std::fabs(deep - dn * p_deep), z * std::sqrt(dn * p_deep) + 1.0);
}
