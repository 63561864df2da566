// Theo1: Stable32's PHASE.DAT value, the tau/m conventions, and the vectorized algorithm against
// the literal double sum (reference_total.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/nbs14.hpp"
#include "core/reference_total.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
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

TEST(Theo1, FastEqualsDefinitionWithLargeOffset) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(500);
  double s = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    s += g(rng);
    x[k] = -3e7 + 2e4 * static_cast<double>(k) + s + g(rng);
  }
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
