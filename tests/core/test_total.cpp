// The total family: published NBS14 / Stable32 values, identities, and the fast algorithms
// against the literal definitions (reference_total.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "imunoise/allan.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/hadamard.hpp"
#include "imunoise/modified_allan.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/total.hpp"
#include "core/nbs14.hpp"
#include "core/offset_random_walk.hpp"
#include "core/reference_total.hpp"

namespace imunoise {
namespace {

std::vector<double> phase_dat() {  // Stable32's PHASE.DAT: NBS14 1000 points integrated
  const auto y = test::nbs14_1000_point_frequency();
  return phase_from_rate(y, 1.0, compensated_mean(y));
}

double one(std::vector<DevPoint> (*f)(std::span<const double>, double,
                                      std::span<const std::size_t>, const DevOptions&),
           const std::vector<double>& x, std::size_t m, std::size_t* n = nullptr) {
  const std::size_t factors[1] = {m};
  const auto points = f(x, 1.0, std::span<const std::size_t>(factors, 1), {});
  if (n != nullptr) *n = points[0].n;
  return points[0].dev;
}

// Random-walk phase (white FM) with a large constant and linear offset: the cancellation guard.
std::vector<double> offset_phase(std::size_t n, unsigned seed) {
  return test::offset_random_walk(n, seed, 1e6, 1e3);
}

TEST(Total, Nbs14TenPointTotdev) {
  const auto y = test::nbs14_10_point_frequency();
  const auto x = phase_from_rate(y, 1.0, compensated_mean(y));
  EXPECT_NEAR(one(totdev, x, 1), 91.22945, 91.22945 * 6e-7);
  EXPECT_NEAR(one(totdev, x, 2), 93.90379, 93.90379 * 6e-7);
}

TEST(Total, Nbs14ThousandPointTotdev) {
  const auto x = phase_dat();
  EXPECT_NEAR(one(totdev, x, 10), 9.134743e-2, 9.134743e-2 * 6e-7);
  EXPECT_NEAR(one(totdev, x, 100), 3.406530e-2, 3.406530e-2 * 6e-7);
}

TEST(Total, Stable32PhaseDat) {
  const auto x = phase_dat();
  std::size_t n = 0;
  EXPECT_NEAR(one(totdev, x, 2, &n), 2.0089e-01, 0.00005e-01 + 1e-9);
  EXPECT_EQ(n, 999u);
  EXPECT_NEAR(one(mtotdev, x, 2, &n), 1.4337e-01, 0.00005e-01 + 1e-9);
  EXPECT_EQ(n, 996u);
  EXPECT_NEAR(one(ttotdev, x, 2, &n), 1.6555e-01, 0.00005e-01 + 1e-9);
  EXPECT_EQ(n, 996u);
  EXPECT_NEAR(one(htotdev, x, 2, &n), 2.0247e-01, 0.00005e-01 + 1e-9);  // no bias correction
  EXPECT_EQ(n, 995u);
}

TEST(Total, Identities) {
  const auto x = offset_phase(400, 7);
  const std::size_t m1[1] = {1};
  EXPECT_NEAR(one(totdev, x, 1), oadev(x, 1.0, m1)[0].dev, 1e-12 * oadev(x, 1.0, m1)[0].dev);
  EXPECT_NEAR(one(htotdev, x, 1), ohdev(x, 1.0, m1)[0].dev, 1e-12 * ohdev(x, 1.0, m1)[0].dev);
  for (const std::size_t m : {1u, 3u, 10u, 33u}) {
    const double tau = static_cast<double>(m);
    EXPECT_NEAR(one(ttotdev, x, m), tau / std::sqrt(3.0) * one(mtotdev, x, m),
                1e-14 * one(ttotdev, x, m));
  }
}

TEST(Total, FastEqualsDefinitionWithLargeOffset) {
  const auto x = offset_phase(301, 11);
  for (std::size_t m = 1; m <= 150; m += (m < 8 ? 1 : 17)) {
    const double ref = test::reference_totdev(x, 1.0, m);
    EXPECT_NEAR(one(totdev, x, m), ref, 1e-10 * ref) << "totdev m=" << m;
  }
  for (std::size_t m = 1; m <= 100; m += (m < 8 ? 1 : 13)) {
    const double ref = test::reference_mtotdev(x, 1.0, m);
    EXPECT_NEAR(one(mtotdev, x, m), ref, 1e-10 * ref) << "mtotdev m=" << m;
  }
  for (std::size_t m = 2; m <= 100; m += (m < 8 ? 1 : 13)) {
    const double ref = test::reference_htotdev(x, 1.0, m);
    EXPECT_NEAR(one(htotdev, x, m), ref, 1e-10 * ref) << "htotdev m=" << m;
  }
}

// Several blocks of subsequences (512 per block), a partial last group of lanes, and a long
// subsequence: the block-local prefix sums and the lane padding must not show.
TEST(Total, FastEqualsDefinitionAcrossBlocksAndLanes) {
  const auto x = offset_phase(1500, 13);
  for (const std::size_t m : {5u, 64u, 171u}) {
    const double ref = test::reference_mtotdev(x, 1.0, m);
    EXPECT_NEAR(one(mtotdev, x, m), ref, 1e-10 * ref) << "mtotdev m=" << m;
    const double href = test::reference_htotdev(x, 1.0, m);
    EXPECT_NEAR(one(htotdev, x, m), href, 1e-10 * href) << "htotdev m=" << m;
  }
}

TEST(Total, ThreadCountDoesNotChangeResults) {
  const auto x = offset_phase(3000, 5);
  const std::size_t factors[3] = {8, 64, 512};
  const auto a = mtotdev(x, 1.0, factors, {1});
  const auto b = mtotdev(x, 1.0, factors, {2});
  for (std::size_t t = 0; t < 3; ++t) EXPECT_EQ(a[t].dev, b[t].dev);
}

TEST(Total, DomainIsChecked) {
  const auto x = offset_phase(30, 1);
  EXPECT_EQ(max_averaging_factor(Estimator::totdev, 30), 14u);
  EXPECT_EQ(max_averaging_factor(Estimator::mtotdev, 30), 10u);
  EXPECT_EQ(max_averaging_factor(Estimator::htotdev, 30), 9u);
  const std::size_t bad[1] = {11};
  EXPECT_THROW(mtotdev(x, 1.0, bad), InputError);
  EXPECT_NO_THROW(compute_deviation(Estimator::mtotdev, x, 1.0, std::vector<std::size_t>{10}));
}

}  // namespace
}  // namespace imunoise
