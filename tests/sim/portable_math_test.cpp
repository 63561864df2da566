// Portable elementary functions: accuracy against long double references.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

#include "imunoise/sim/portable_math.hpp"
#include "imunoise/sim/rng.hpp"

namespace ps = imunoise::sim::portable;
using imunoise::sim::Xoshiro256StarStar;

namespace {

// |a - b| in units of the last place of b (the reference rounded to double).
double ulps(double a, long double reference) {
  const double b = static_cast<double>(reference);
  if (a == b) return 0.0;
  const double spacing = std::nextafter(std::fabs(b), INFINITY) - std::fabs(b);
  return static_cast<double>(std::fabs(static_cast<long double>(a) - reference) / spacing);
}

}  // namespace

TEST(PortableMath, ExpWithinTwoUlp) {
  Xoshiro256StarStar rng(11);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double x = -740.0 + 1449.0 * rng.uniform();
    worst = std::max(worst, ulps(ps::exp(x), std::exp(static_cast<long double>(x))));
  }
  for (int i = 0; i < 100000; ++i) {  // the ziggurat's range
    const double x = -7.0 * rng.uniform();
    worst = std::max(worst, ulps(ps::exp(x), std::exp(static_cast<long double>(x))));
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(ps::exp(0.0), 1.0);
  EXPECT_EQ(ps::exp(-800.0), 0.0);
  EXPECT_TRUE(std::isinf(ps::exp(710.0)));
}

TEST(PortableMath, Expm1WithinTwoUlp) {
  Xoshiro256StarStar rng(12);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double x = std::ldexp(rng.uniform() - 0.5, -static_cast<int>(rng() % 60));
    worst = std::max(worst, ulps(ps::expm1(x), std::expm1(static_cast<long double>(x))));
    const double y = -30.0 + 60.0 * rng.uniform();
    worst = std::max(worst, ulps(ps::expm1(y), std::expm1(static_cast<long double>(y))));
  }
  EXPECT_LE(worst, 2.0);
}

TEST(PortableMath, LogWithinTwoUlp) {
  Xoshiro256StarStar rng(13);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double x = std::ldexp(0.5 + rng.uniform(), static_cast<int>(rng() % 2000) - 1000);
    worst = std::max(worst, ulps(ps::log(x), std::log(static_cast<long double>(x))));
    const double y = 1.0 - rng.uniform();  // (0, 1], as used by the ziggurat's tail
    worst = std::max(worst, ulps(ps::log(y), std::log(static_cast<long double>(y))));
  }
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(ps::log(1.0), 0.0);
  EXPECT_TRUE(std::isnan(ps::log(-1.0)));
  EXPECT_TRUE(std::isnan(ps::log(0.0)));
}

TEST(PortableMath, SinCosOfCycles) {
  Xoshiro256StarStar rng(14);
  long double worst = 0.0L;
  for (int i = 0; i < 100000; ++i) {
    const double c = (rng.uniform() - 0.5) * 2.0e6;
    const auto [s, co] = ps::sincos_cycles(c);
    // Reference: reduce exactly in long double, then evaluate.
    const long double frac = static_cast<long double>(c) - std::nearbyint(static_cast<long double>(c));
    const long double a = 2.0L * std::numbers::pi_v<long double> * frac;
    worst = std::max({worst, std::fabs(static_cast<long double>(s) - std::sin(a)),
                      std::fabs(static_cast<long double>(co) - std::cos(a))});
  }
  EXPECT_LE(static_cast<double>(worst), 2e-16);
  const auto quarter = ps::sincos_cycles(0.25);
  EXPECT_EQ(quarter.first, 1.0);
  EXPECT_EQ(quarter.second, 0.0);
  EXPECT_EQ(ps::sincos_cycles(0.5).second, -1.0);
}
