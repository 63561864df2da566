// totdev_reflected_range: totdev over AllanTools' range m <= N-1 (the reflection's full reach),
// against the literal SP 1065 definition, and equal to totdev where both are defined.
#include <gtest/gtest.h>

#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/total.hpp"
#include "core/offset_random_walk.hpp"
#include "core/reference_total.hpp"

namespace imunoise {
namespace {

TEST(TotalReflectedRange, EqualsTheDefinitionUpToNMinus1) {
  // Large constant and linear offsets: the cancellation guard.
  const auto x = test::offset_random_walk(101, 17, 1e6, 1e3);
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= 100; m += (m < 8 ? 1 : 9)) factors.push_back(m);
  factors.push_back(100);  // m = N - 1
  const auto points = totdev_reflected_range(x, 0.5, factors);
  ASSERT_EQ(points.size(), factors.size());
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const double ref = test::reference_totdev(x, 0.5, factors[t]);
    EXPECT_NEAR(points[t].dev, ref, 1e-10 * ref) << "m=" << factors[t];
    EXPECT_EQ(points[t].n, 99u);
    EXPECT_EQ(points[t].m, factors[t]);
    EXPECT_DOUBLE_EQ(points[t].tau_s, 0.5 * static_cast<double>(factors[t]));
  }
}

TEST(TotalReflectedRange, SameAsTotdevInItsDomain) {
  const auto x = test::offset_random_walk(64, 3, 1e3, 1.0);
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= max_averaging_factor(Estimator::totdev, x.size()); ++m) factors.push_back(m);
  const auto a = totdev(x, 1.0, factors);
  const auto b = totdev_reflected_range(x, 1.0, factors);
  for (std::size_t t = 0; t < factors.size(); ++t) EXPECT_EQ(a[t].dev, b[t].dev);
}

TEST(TotalReflectedRange, RangeIsChecked) {
  const auto x = test::offset_random_walk(30, 1, 0.0, 0.0);
  EXPECT_THROW(totdev_reflected_range(x, 1.0, std::vector<std::size_t>{30}), InputError);
  EXPECT_THROW(totdev_reflected_range(x, 1.0, std::vector<std::size_t>{0}), InputError);
  EXPECT_THROW(totdev_reflected_range(x, 0.0, std::vector<std::size_t>{1}), InputError);
  EXPECT_THROW(totdev_reflected_range(std::vector<double>{1.0, 2.0}, 1.0, std::vector<std::size_t>{1}),
               InputError);
  EXPECT_NO_THROW(totdev_reflected_range(x, 1.0, std::vector<std::size_t>{29}));
}

}  // namespace
}  // namespace imunoise
