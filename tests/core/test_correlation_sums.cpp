// The difference sums of every factor through FFT correlations (src/core/correlation_sums.hpp)
// against long-double direct sums: the values where the rounding bound accepts them, the bound
// itself where it does not, the routing in the engine, and R(n) of the noise identification.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include "../../src/core/correlation_sums.hpp"
#include "../../src/core/difference_sums.hpp"
#include "core/offset_random_walk.hpp"
#include "imunoise/confidence/noise_id.hpp"

namespace imunoise {
namespace {

long double direct_sum(const std::vector<double>& x, int order, std::size_t m) {
  long double sum = 0.0L;
  for (std::size_t k = 0; k + static_cast<std::size_t>(order) * m < x.size(); ++k) {
    const long double d = order == 2 ? static_cast<long double>(x[k + 2 * m]) - 2.0L * x[k + m] + x[k]
                                     : static_cast<long double>(x[k + 3 * m]) - 3.0L * x[k + 2 * m] +
                                           3.0L * x[k + m] - x[k];
    sum += d * d;
  }
  return sum;
}

struct Signal {
  std::string name;
  std::vector<double> phase;
};

// White PM (phase itself white, on an offset), white FM on an offset and drift (random-walk
// phase: the case the detrending is for), and random-walk FM (phase a double integral: most
// small factors must be rejected).
std::vector<Signal> signals(std::size_t n) {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> white(n), walk_rate(n);
  double rate = 0.0, phase = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    white[i] = 1e3 + g(rng);
    rate += g(rng);
    phase += rate;
    walk_rate[i] = phase;
  }
  return {{"white PM", white},
          {"white FM on offset and drift", test::offset_random_walk(n, 7, 1e6, 30.0)},
          {"random-walk FM", walk_rate}};
}

std::vector<std::size_t> every_factor(std::size_t n, int order) {
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; static_cast<std::size_t>(order) * m < n; ++m) factors.push_back(m);
  return factors;
}

// Every factor of three kinds of record, orders 2 and 3: the actual rounding never exceeds the
// stated bound, sums the engine accepts (bound <= 5e-13) match to 1e-12, and the bound is not so loose
// that it rejects the bulk of a white-FM record's factors.
TEST(CorrelationSums, WithinTheirBoundOfDirectSums) {
  const std::size_t n = 20001;
  for (const Signal& s : signals(n)) {
    for (const int order : {2, 3}) {
      const auto factors = every_factor(n, order);
      const auto sums = detail::correlation_difference_sums(s.phase, order, factors, 2);
      std::size_t accepted = 0;
      for (std::size_t t = 0; t < factors.size(); ++t) {
        const long double exact = direct_sum(s.phase, order, factors[t]);
        const double error = std::fabs(static_cast<double>(sums.sum_sq[t] - exact));
        if (std::isfinite(sums.relative_bound[t])) {
          EXPECT_LE(error, sums.relative_bound[t] * sums.sum_sq[t])
              << s.name << " order " << order << " m=" << factors[t];
        }
        if (sums.relative_bound[t] <= 5e-13) {
          ++accepted;
          EXPECT_LE(error, 1e-12 * static_cast<double>(exact)) << s.name << " order " << order << " m=" << factors[t];
        }
      }
      if (s.name != "random-walk FM") {
        EXPECT_GT(accepted, factors.size() * 8 / 10) << s.name << " order " << order;
      }
    }
  }
}

TEST(CorrelationSums, SameForAnyThreadCount) {
  const auto phase = test::offset_random_walk(30011, 3, 1e4, 2.0, 0.5);
  const auto factors = every_factor(phase.size(), 3);
  const auto one = detail::correlation_difference_sums(phase, 3, factors, 1);
  const auto two = detail::correlation_difference_sums(phase, 3, factors, 2);
  EXPECT_EQ(one.sum_sq, two.sum_sq);
  EXPECT_EQ(one.relative_bound, two.relative_bound);
}

// The engine takes every factor of a long record through the correlations and the rest (small
// factors, few starts) directly: sampled factors of both kinds against the definition.
TEST(CorrelationSums, EngineRoutesEveryFactorOfALongRecord) {
  const auto phase = test::offset_random_walk(100001, 5, -3e5, 12.0);
  for (const int order : {2, 3}) {
    const auto factors = every_factor(phase.size(), order);
    const auto sums = detail::overlapping_difference_sums(phase, order, factors, 2);
    for (std::size_t t = 0; t < factors.size(); t += (t < 3000 ? 1 : 97)) {
      const long double exact = direct_sum(phase, order, factors[t]);
      EXPECT_NEAR(sums.sum_sq[t] / static_cast<double>(exact), 1.0, 1e-12) << "order " << order << " m=" << factors[t];
      EXPECT_EQ(sums.n[t], phase.size() - static_cast<std::size_t>(order) * factors[t]);
    }
  }
}

// R(n) from the correlation sums against rn_ratio at every factor of B1's range.
TEST(CorrelationSums, RnRatiosMatchTheDirectRatio) {
  const auto phase = test::offset_random_walk(24001, 9, 5e3, -4.0, 2.0);
  std::vector<std::size_t> factors;
  for (std::size_t m = phase.size() / 30; 3 * m <= phase.size(); ++m) factors.push_back(m);
  const auto rn = rn_ratios(phase, factors, 2);
  std::size_t measured = 0;
  for (std::size_t t = 0; t < factors.size(); ++t) {
    if (std::isnan(rn[t])) continue;
    ++measured;
    EXPECT_NEAR(rn[t] / rn_ratio(phase, factors[t]), 1.0, 1e-9) << "m=" << factors[t];
  }
  EXPECT_GT(measured, factors.size() * 9 / 10);
}

}  // namespace
}  // namespace imunoise
