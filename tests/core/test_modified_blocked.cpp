// The blocked modified-Allan engine (vector window recursion, small factors run together over
// chunks, large ones over their own segments) against an independent formulation: window sums
// as differences of long-double prefix sums of the second differences, O(N) per factor, so long
// records and large factors can be checked term for term where the literal definition
// (O(N m) per factor) would take minutes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/offset_random_walk.hpp"
#include "core/reference_estimators.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise {
namespace {

// mdev at m from long-double prefix sums: E[k] = sum_{i<k} e_i, v_j = E[j+m] - E[j].
double prefix_mdev(const std::vector<double>& x, double tau0, std::size_t m) {
  const std::size_t n = x.size();
  const std::size_t count = n - 2 * m;  // second differences e_0 .. e_{n-2m-1}
  std::vector<long double> prefix(count + 1, 0.0L);
  for (std::size_t i = 0; i < count; ++i) {
    prefix[i + 1] = prefix[i] + (static_cast<long double>(x[i + 2 * m]) - 2.0L * x[i + m] + x[i]);
  }
  const std::size_t windows = n - 3 * m + 1;
  long double sum = 0.0L;
  for (std::size_t j = 0; j < windows; ++j) {
    const long double v = prefix[j + m] - prefix[j];
    sum += v * v;
  }
  const long double md = static_cast<long double>(m);
  const long double tau = md * tau0;
  return static_cast<double>(std::sqrt(sum / (2.0L * md * md * windows)) / tau);
}

std::vector<double> white_fm_phase(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::vector<double> rate(n - 1);
  for (auto& v : rate) v = static_cast<double>(engine() >> 11) * 0x1.0p-53 - 0.5;
  return phase_from_rate(rate, 0.01, compensated_mean(rate));
}

// The prefix reference itself against the literal definition, where that is affordable.
TEST(ModifiedBlocked, PrefixReferenceAgreesWithTheDefinition) {
  const auto x = white_fm_phase(3001, 21);
  for (const std::size_t m : {1u, 2u, 7u, 64u, 333u, 1000u}) {
    EXPECT_NEAR(prefix_mdev(x, 0.01, m) / test::reference_deviation(Estimator::mdev, x, 0.01, m),
                1.0, 1e-14)
        << m;
  }
}

// Factors on both sides of the small/large split (4096), segment and chunk boundaries included
// (records longer than a 65,536-start chunk), and the ragged end of the record.
TEST(ModifiedBlocked, MatchesPrefixReferenceOnLongRecords) {
  for (const std::size_t n : {140001u, 262144u}) {
    const auto x = white_fm_phase(n, 22);
    std::vector<std::size_t> factors{1, 2, 3, 5, 8, 31, 100, 1024, 4095, 4096, 4097, 5000, 16384,
                                     20000};
    for (std::size_t m = 1; 3 * m <= n; m *= 2) factors.push_back(m);
    factors.push_back(n / 3);
    for (const auto& p : compute_deviation(Estimator::mdev, x, 0.01, factors)) {
      EXPECT_NEAR(p.dev / prefix_mdev(x, 0.01, p.m), 1.0, 1e-12) << "n=" << n << " m=" << p.m;
      EXPECT_EQ(p.n, n - 3 * p.m + 1);
    }
  }
}

// Short records whose factors are multiples of the tile columns (128 here): a handful of tile
// rows, the last window ending exactly at the last sample, against the literal definition.
TEST(ModifiedBlocked, TilePathOnShortRecordsMatchesTheDefinition) {
  for (const std::size_t n : {384u, 385u, 400u, 517u, 1000u, 1153u}) {
    const auto x = white_fm_phase(n, 25);
    std::vector<std::size_t> factors;
    for (std::size_t m = 128; 3 * m <= n; m += 128) factors.push_back(m);
    factors.push_back(1);
    factors.push_back(n / 3);
    for (const auto& p : compute_deviation(Estimator::mdev, x, 0.01, factors)) {
      EXPECT_NEAR(p.dev / test::reference_deviation(Estimator::mdev, x, 0.01, p.m), 1.0, 1e-12)
          << "n=" << n << " m=" << p.m;
    }
  }
}

// Phase far from zero and tilted (a rate offset left in): the recursion's increments cancel the
// offset and slope term by term; the result still matches to 1e-10.
// The power-of-two factors below the tile columns (256 at 6e5 samples) run by doubling.
TEST(ModifiedBlocked, OffsetAndSlopeDoNotDegradeResults) {
  for (const std::size_t n : {200000u, 600000u}) {
    const auto x = test::offset_random_walk(n, 23, 1e6, 50.0);
    const std::vector<std::size_t> factors{1, 2, 16, 64, 128, 200, 256, 300, 4096, 5000, 30000};
    for (const auto& p : compute_deviation(Estimator::mdev, x, 1.0, factors)) {
      EXPECT_NEAR(p.dev / prefix_mdev(x, 1.0, p.m), 1.0, 1e-10) << "n=" << n << " m=" << p.m;
    }
  }
}

TEST(ModifiedBlocked, ThreadCountDoesNotChangeABit) {
  const auto x = white_fm_phase(300001, 24);
  const auto factors = averaging_factors(TauGrid{}, 100.0, max_averaging_factor(Estimator::mdev, x.size()));
  const auto one = compute_deviation(Estimator::mdev, x, 0.01, factors, {1});
  for (const unsigned threads : {2u, 3u, 8u}) {
    const auto many = compute_deviation(Estimator::mdev, x, 0.01, factors, {threads});
    for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(one[i].dev, many[i].dev) << threads;
  }
}

}  // namespace
}  // namespace imunoise
