#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "imunoise/finite.hpp"

namespace {

TEST(FirstNonFinite, AllFiniteGivesSize) {
  std::vector<double> v(10'000, 1e300);
  EXPECT_EQ(imunoise::first_non_finite(v), v.size());
  EXPECT_EQ(imunoise::first_non_finite({}), 0u);
}

TEST(FirstNonFinite, FindsTheFirstOfEachKindAtAnyPosition) {
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  // Positions at block edges (blocks of 4096) and in the tail.
  for (const double b : bad) {
    for (const std::size_t pos : {0u, 1u, 4095u, 4096u, 4097u, 12287u, 12299u}) {
      std::vector<double> v(12'300, -2.5);
      v[pos] = b;
      if (pos + 7 < v.size()) v[pos + 7] = b;  // a later one must not be reported
      EXPECT_EQ(imunoise::first_non_finite(v), pos) << b << " at " << pos;
    }
  }
}

TEST(FirstNonFinite, LargestFiniteValuesAreFinite) {
  std::vector<double> v{std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                        std::numeric_limits<double>::denorm_min()};
  EXPECT_EQ(imunoise::first_non_finite(v), v.size());
}

}  // namespace

namespace {

TEST(FirstNonFinite, ThreadCountDoesNotChangeTheAnswer) {
  // Several 1 M chunks, bad values in two of them: the earlier one is reported.
  std::vector<double> v(3'500'000, 0.25);
  v[2'900'000] = std::numeric_limits<double>::quiet_NaN();
  v[1'048'577] = std::numeric_limits<double>::infinity();
  for (const unsigned threads : {1u, 2u, 0u}) {
    EXPECT_EQ(imunoise::first_non_finite(v, threads), 1'048'577u) << threads;
  }
  v[1'048'577] = 0.0;
  EXPECT_EQ(imunoise::first_non_finite(v, 2), 2'900'000u);
}

}  // namespace
