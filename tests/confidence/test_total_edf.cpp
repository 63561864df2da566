// EDF and confidence bounds of the total family, Theo1 and the time-error statistics (SP 1065),
// against Stable32's printed PHASE.DAT bounds where they exist, and the formulas' own values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/total.hpp"
#include "core/nbs14.hpp"

namespace imunoise {
namespace {

TEST(TotalEdf, Sp1065Formulas) {
  // totdev, Table 7: b N/m - c.
  EXPECT_NEAR(edf(Estimator::totdev, 0, 2, 1001).value, 1.5 * 1001 / 2, 1e-9);
  EXPECT_NEAR(edf(Estimator::totdev, -2, 10, 1001).value, 0.93 * 100.1 - 0.36, 1e-9);
  EXPECT_EQ(edf(Estimator::totdev, -1, 10, 1001).method, EdfMethod::sp1065);
  // mtotdev and ttotdev, Table 8.
  EXPECT_NEAR(edf(Estimator::mtotdev, 2, 4, 1000).value, 1.90 * 250 - 2.10, 1e-9);
  EXPECT_NEAR(edf(Estimator::ttotdev, -2, 4, 1000).value, 0.75 * 250 - 0.31, 1e-9);
  // htotdev: ohdev's Greenhall-Riley EDF below m = 16, the Howe et al. form above.
  const DifferenceVariance ohdev_structure{3, false, true};
  EXPECT_NEAR(edf(Estimator::htotdev, 0, 4, 1000).value,
              greenhall_riley_edf(0, ohdev_structure, 4, 1000), 1e-9);
  EXPECT_EQ(edf(Estimator::htotdev, 0, 4, 1000).method, EdfMethod::greenhall_riley);
  EXPECT_NEAR(edf(Estimator::htotdev, -1, 20, 1000).value, 50.0 / (0.868 + 1.140 / 50.0), 1e-9);
  // theo1, white FM at N = 1001, m = 10 (r = 7.5), by hand.
  const double r = 7.5;
  const double N = 1001;
  const double expected = ((4.1 * N + 0.8) / r - (3.1 * N + 6.5) / N) * std::pow(r, 1.5) /
                          (std::pow(r, 1.5) + 5.2);
  EXPECT_NEAR(edf(Estimator::theo1, 0, 10, 1001).value, expected, 1e-9 * expected);
  EXPECT_NEAR(expected, 434.27, 0.01);
  // Outside the domains: no EDF.
  EXPECT_EQ(edf(Estimator::theo1, -3, 10, 1001).method, EdfMethod::not_available);
  EXPECT_EQ(edf(Estimator::mtie, 0, 10, 1001).method, EdfMethod::not_available);
  EXPECT_EQ(edf(Estimator::tierms, 0, 10, 1001).method, EdfMethod::not_available);
  EXPECT_FALSE(alpha_in_domain(Estimator::mtie, 0));
  EXPECT_TRUE(alpha_in_domain(Estimator::htotdev, -4));
  EXPECT_FALSE(alpha_in_domain(Estimator::totdev, -3));
}

// Stable32 1.60 on PHASE.DAT, totdev AF 2: 1.9592e-01 < 2.0089e-01 < 2.0625e-01 (68.3%).
// SP 1065's white-FM EDF 1.5 N/m = 750.75 gives bounds within 1.1e-4 and 1.8e-4 relative of the
// printed ones (the 5-digit printing alone allows 5e-5; Stable32's own EDF is ~1% higher).
TEST(TotalEdf, TotdevBoundsNearStable32) {
  const auto x = test::nbs14_phase_dat();
  std::vector<std::size_t> factors{2};
  auto points = compute_deviation(Estimator::totdev, x, 1.0, factors);
  const auto info = fill_confidence(points, Estimator::totdev, x, 0.683);
  EXPECT_EQ(points[0].alpha, 0);
  EXPECT_EQ(info[0].edf.method, EdfMethod::sp1065);
  EXPECT_NEAR(points[0].ci_low, 1.9592e-01, 2.5e-4 * 1.9592e-01);
  EXPECT_NEAR(points[0].ci_high, 2.0625e-01, 2.5e-4 * 2.0625e-01);
}

// Every new estimator goes through fill_confidence: noise identified through its
// finite-difference proxy, an EDF where one is defined, none for MTIE / TIE rms.
TEST(TotalEdf, FillConfidenceForEveryEstimator) {
  const auto x = test::nbs14_phase_dat();
  for (const Estimator e : {Estimator::totdev, Estimator::mtotdev, Estimator::ttotdev,
                            Estimator::htotdev, Estimator::theo1, Estimator::mtie,
                            Estimator::tierms}) {
    std::vector<std::size_t> factors{2, 4, 8};
    auto points = compute_deviation(e, x, 1.0, factors);
    const auto info = fill_confidence(points, e, x, 0.683);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (e == Estimator::mtie || e == Estimator::tierms) {
        EXPECT_TRUE(std::isnan(points[i].edf));
        EXPECT_FALSE(info[i].note.empty());
      } else {
        EXPECT_EQ(points[i].alpha, 0) << estimator_name(e) << " m=" << points[i].m;
        EXPECT_GT(points[i].edf, 1.0) << estimator_name(e);
        EXPECT_LT(points[i].ci_low, points[i].dev);
        EXPECT_GT(points[i].ci_high, points[i].dev);
      }
    }
  }
}

// Stable32 1.60, PHASE.DAT htotdev AF 2: 2.0247e-01 raw (alpha = 2: no correction) and
// 2.0297e-01 bias-corrected for white FM (alpha = 0).
TEST(TotalBias, HtotdevMatchesStable32) {
  const auto x = test::nbs14_phase_dat();
  std::vector<std::size_t> factors{2};
  auto points = compute_deviation(Estimator::htotdev, x, 1.0, factors);
  points[0].alpha = 0;
  EXPECT_EQ(apply_bias_correction(points, Estimator::htotdev, x.size()), 1u);
  EXPECT_NEAR(points[0].dev, 2.0297e-01, 0.00005e-01);
  EXPECT_TRUE(std::isnan(bias_variance_factor(Estimator::htotdev, 2, 2, 1001)));
  EXPECT_TRUE(std::isnan(bias_variance_factor(Estimator::htotdev, 0, 1, 1001)));
}

TEST(TotalBias, Factors) {
  EXPECT_DOUBLE_EQ(bias_variance_factor(Estimator::totdev, 0, 10, 1000), 1.0);
  EXPECT_NEAR(bias_variance_factor(Estimator::totdev, -2, 100, 1000), 1.0 / (1.0 - 0.075), 1e-15);
  EXPECT_NEAR(bias_variance_factor(Estimator::mtotdev, 0, 8, 1000), 1.0 / 0.73, 1e-15);
  EXPECT_NEAR(bias_variance_factor(Estimator::theo1, 0, 10, 1000), 1.0, 1e-15);
  EXPECT_NEAR(bias_variance_factor(Estimator::theo1, 2, 10, 1000),
              0.09 + 0.74 / std::pow(7.5, 0.40), 1e-15);
  EXPECT_TRUE(std::isnan(bias_variance_factor(Estimator::oadev, 0, 10, 1000)));
}

}  // namespace
}  // namespace imunoise
