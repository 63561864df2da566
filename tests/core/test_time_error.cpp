// MTIE and TIE rms: Stable32's PHASE.DAT values and the O(N) algorithms against the definitions.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/nbs14.hpp"
#include "core/reference_total.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/time_error.hpp"

namespace imunoise {
namespace {

TEST(TimeError, Stable32PhaseDat) {
  const auto y = test::nbs14_1000_point_frequency();
  const auto x = phase_from_rate(y, 1.0, compensated_mean(y));
  const std::size_t m3[1] = {3};
  const auto a = mtie(x, 1.0, m3);
  EXPECT_NEAR(a[0].dev, 1.2984, 0.00005 + 1e-12);
  EXPECT_EQ(a[0].n, 998u);
  const std::size_t m2[1] = {2};
  const auto b = tierms(x, 1.0, m2);
  EXPECT_NEAR(b[0].dev, 4.0240e-01, 0.00005e-01 + 1e-12);
  EXPECT_EQ(b[0].n, 999u);
}

TEST(TimeError, FastEqualsDefinition) {
  std::mt19937_64 rng(21);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(700);
  double s = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    s += g(rng);
    x[k] = 5e8 + s + 0.3 * static_cast<double>(k % 17);
  }
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m < x.size(); m += 1 + m / 3) factors.push_back(m);
  factors.push_back(x.size() - 1);
  const auto a = mtie(x, 1.0, factors);
  const auto b = tierms(x, 1.0, factors);
  for (std::size_t t = 0; t < factors.size(); ++t) {
    EXPECT_EQ(a[t].dev, test::reference_mtie(x, factors[t])) << "m=" << factors[t];
    const double ref = test::reference_tierms(x, factors[t]);
    EXPECT_NEAR(b[t].dev, ref, 1e-12 * ref) << "m=" << factors[t];
  }
}

}  // namespace
}  // namespace imunoise
