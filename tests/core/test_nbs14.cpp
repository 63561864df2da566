// Published NBS14 deviations (NIST SP 1065, Riley) reproduced to their printed precision.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/nbs14.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/phase.hpp"

namespace imunoise {
namespace {

struct Published {
  Estimator estimator;
  std::size_t m;
  double dev;
};

// The tables print 7 significant digits: a correct value is within half a unit of the last
// digit, i.e. < 6e-7 relative for every entry here.
constexpr double kPrintedPrecision = 6e-7;

void expect_published(const std::vector<double>& frequency, const std::vector<Published>& table) {
  const auto phase = phase_from_rate(frequency, 1.0, compensated_mean(frequency));
  for (const auto& row : table) {
    const std::size_t factors[] = {row.m};
    const auto points = compute_deviation(row.estimator, phase, 1.0, factors);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_NEAR(points[0].dev / row.dev, 1.0, kPrintedPrecision)
        << estimator_name(row.estimator) << " m=" << row.m << " got " << points[0].dev;
  }
}

TEST(Nbs14, TenPointSet) {
  expect_published(test::nbs14_10_point_frequency(),
                   {{Estimator::adev, 1, 91.22945},  {Estimator::adev, 2, 115.8082},
                    {Estimator::oadev, 1, 91.22945}, {Estimator::oadev, 2, 85.95287},
                    {Estimator::mdev, 1, 91.22945},  {Estimator::mdev, 2, 74.78849},
                    {Estimator::hdev, 1, 70.80608},  {Estimator::hdev, 2, 116.7980},
                    {Estimator::ohdev, 1, 70.80607}, {Estimator::ohdev, 2, 85.61487},
                    {Estimator::tdev, 1, 52.67135},  {Estimator::tdev, 2, 86.35831}});
}

TEST(Nbs14, ThousandPointSet) {
  expect_published(test::nbs14_1000_point_frequency(),
                   {{Estimator::adev, 1, 2.922319e-1},   {Estimator::adev, 10, 9.965736e-2},
                    {Estimator::adev, 100, 3.897804e-2}, {Estimator::oadev, 1, 2.922319e-1},
                    {Estimator::oadev, 10, 9.159953e-2}, {Estimator::oadev, 100, 3.241343e-2},
                    {Estimator::mdev, 1, 2.922319e-1},   {Estimator::mdev, 10, 6.172376e-2},
                    {Estimator::mdev, 100, 2.170921e-2}, {Estimator::hdev, 1, 2.943883e-1},
                    {Estimator::hdev, 10, 1.052754e-1},  {Estimator::hdev, 100, 3.910860e-2},
                    {Estimator::ohdev, 1, 2.943883e-1},  {Estimator::ohdev, 10, 9.581083e-2},
                    {Estimator::ohdev, 100, 3.237638e-2}});
}

// The 10-point phase values printed in SP 1065 are the frequency set integrated from 0.
TEST(Nbs14, PhaseOfTenPointSetMatchesPublishedPhase) {
  const auto freq = test::nbs14_10_point_frequency();
  const auto phase = phase_from_rate(freq, 1.0, compensated_mean(freq));
  const double published[] = {0, 103.11111, 123.22222, 157.33333, 166.44444,
                              48.55555, -96.33333, -2.22222, 111.88889, 0};
  ASSERT_EQ(phase.size(), 10u);
  for (std::size_t k = 0; k < phase.size(); ++k) EXPECT_NEAR(phase[k], published[k], 1e-5);
}

}  // namespace
}  // namespace imunoise
