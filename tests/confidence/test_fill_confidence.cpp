// Confidence intervals of whole deviation curves: Stable32's PHASE.DAT rows end to end, and the
// fallbacks and messages at the edges.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "core/nbs14.hpp"
#include "power_law_noise.hpp"

namespace imunoise {
namespace {

double rel(double a, double b) { return std::fabs(a / b - 1.0); }

TEST(FillConfidence, ReproducesStable32OnPhaseDat) {
  // Stable32 1.60, oadev, 68.3%: m = 1: 2.9223e-01 in 2.8515e-01 .. 2.9987e-01 (n 999);
  // m = 128: 2.7674e-02 in 2.3045e-02 .. 3.7027e-02 (n 745). Required: 1e-3 relative.
  // Measured: bounds within 1.5e-4 (m = 1) and 9e-5 (m = 128). White FM is identified at m = 1
  // (lag-1 ACF); at m = 128 only 7 rate averages remain, too few for B1, and the noise type of
  // the previous tau is used, as Stable32 does.
  const std::vector<double> x = test::nbs14_phase_dat();
  const std::vector<std::size_t> factors{1, 128};
  std::vector<DevPoint> points = compute_deviation(Estimator::oadev, x, 1.0, factors);
  ASSERT_EQ(points.size(), 2u);
  const auto info = fill_confidence(points, Estimator::oadev, x);
  ASSERT_EQ(info.size(), 2u);

  EXPECT_LT(rel(points[0].dev, 2.922319e-01), 1e-6);
  EXPECT_EQ(points[0].n, 999u);
  EXPECT_EQ(points[0].alpha, 0);
  EXPECT_EQ(info[0].noise.method, NoiseIdMethod::lag1_acf);
  EXPECT_EQ(info[0].edf.method, EdfMethod::greenhall_riley);
  EXPECT_NEAR(points[0].edf, 782.03, 0.01);
  EXPECT_LT(rel(points[0].ci_low, 2.8515e-01), 1e-3);
  EXPECT_LT(rel(points[0].ci_high, 2.9987e-01), 1e-3);

  EXPECT_LT(rel(points[1].dev, 2.7674e-02), 2e-5);
  EXPECT_EQ(points[1].n, 745u);
  EXPECT_EQ(points[1].alpha, 0);
  EXPECT_NEAR(points[1].edf, 9.5508, 1e-4);
  EXPECT_LT(rel(points[1].ci_low, 2.3045e-02), 1e-3);
  EXPECT_LT(rel(points[1].ci_high, 3.7027e-02), 1e-3);
  EXPECT_TRUE(info[0].note.empty()) << info[0].note;
  EXPECT_EQ(info[1].noise.method, NoiseIdMethod::previous_tau);
  EXPECT_NE(info[1].note.find("too few samples for noise identification (oadev at m = 128)"),
            std::string::npos)
      << info[1].note;
}

TEST(FillConfidence, OtherPhaseDatRows) {
  // mdev and non-overlapping hdev at m = 2 (references.md), identified as white FM.
  const std::vector<double> x = test::nbs14_phase_dat();
  const std::vector<std::size_t> factors{2};
  std::vector<DevPoint> mdev = compute_deviation(Estimator::mdev, x, 1.0, factors);
  fill_confidence(mdev, Estimator::mdev, x);
  EXPECT_EQ(mdev[0].n, 996u);
  EXPECT_EQ(mdev[0].alpha, 0);
  EXPECT_LT(rel(mdev[0].ci_low, 1.5336e-01), 1e-3);
  EXPECT_LT(rel(mdev[0].ci_high, 1.6355e-01), 1e-3);
  std::vector<DevPoint> hdev = compute_deviation(Estimator::hdev, x, 1.0, factors);
  fill_confidence(hdev, Estimator::hdev, x);
  EXPECT_EQ(hdev[0].n, 498u);
  EXPECT_EQ(hdev[0].alpha, 0);
  EXPECT_LT(rel(hdev[0].ci_low, 1.9887e-01), 1e-3);
  EXPECT_LT(rel(hdev[0].ci_high, 2.1659e-01), 1e-3);
}

TEST(FillConfidence, ForcedNoiseTypeAndLevel) {
  const std::vector<double> x = test::nbs14_phase_dat();
  const std::vector<std::size_t> factors{1, 8, 64};
  std::vector<DevPoint> points = compute_deviation(Estimator::oadev, x, 1.0, factors);
  ConfidenceOptions options;
  options.forced_alpha = -1;
  options.level = 0.95;
  const auto info = fill_confidence(points, Estimator::oadev, x, options);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].alpha, -1);
    EXPECT_EQ(info[i].noise.method, NoiseIdMethod::forced);
    EXPECT_DOUBLE_EQ(points[i].edf, edf(Estimator::oadev, -1, points[i].m, x.size()).value);
    const ConfidenceInterval ci = chi2_interval(points[i].dev, points[i].edf, 0.95);
    EXPECT_DOUBLE_EQ(points[i].ci_low, ci.low);
    EXPECT_DOUBLE_EQ(points[i].ci_high, ci.high);
  }

  options.forced_alpha = -3;  // outside the Allan family
  try {
    fill_confidence(points, Estimator::oadev, x, options);
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("alpha = -3 (flicker-walk FM) is outside the domain of oadev"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("-2 .. 2"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(fill_confidence(points, Estimator::ohdev, x, 0.683, -3));
  EXPECT_THROW(fill_confidence(points, Estimator::oadev, x, 1.5), InputError);
  EXPECT_THROW(fill_confidence(points, Estimator::oadev, x, 0.0), InputError);
}

TEST(FillConfidence, LargestTausReuseTheLastIdentifiedNoiseType) {
  // 41 phase points: m = 1, 2, 4 are identified by B1 (40, 20, 10 rate averages); at m = 8 and
  // 16 fewer than 8 averages remain and the alpha of m = 4 is carried, as Stable32 does; the
  // note on the first of them says so for both.
  test::Gaussian gaussian(21);
  const std::vector<double> x = test::power_law_phase(0, 41, gaussian);
  const std::vector<std::size_t> factors{16, 1, 8, 2, 4};  // any order
  std::vector<DevPoint> points = compute_deviation(Estimator::oadev, x, 1.0, factors);
  const auto info = fill_confidence(points, Estimator::oadev, x);
  std::size_t i16 = 0, i8 = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].m == 16) i16 = i;
    if (points[i].m == 8) i8 = i;
  }
  EXPECT_EQ(info[i16].noise.method, NoiseIdMethod::previous_tau);
  EXPECT_EQ(info[i8].noise.method, NoiseIdMethod::previous_tau);
  EXPECT_EQ(points[i16].alpha, points[i8].alpha);
  EXPECT_NE(info[i8].note.find("too few samples for noise identification (oadev at m = 8)"),
            std::string::npos)
      << info[i8].note;
  EXPECT_NE(info[i8].note.find("identified at a smaller tau"), std::string::npos);
  EXPECT_NE(info[i8].note.find("the same for the larger tau at m = 16"), std::string::npos)
      << info[i8].note;
  EXPECT_TRUE(info[i16].note.empty()) << info[i16].note;
  EXPECT_TRUE(std::isfinite(points[i16].ci_low) && std::isfinite(points[i16].ci_high));
  EXPECT_LT(points[i16].ci_low, points[i16].dev);
  EXPECT_GT(points[i16].ci_high, points[i16].dev);
}

TEST(FillConfidence, NoNoiseTypeAtAllUsesTheLabelledIeee952Edf) {
  const std::vector<double> x{0.0, 1.0, -0.5, 0.7};  // 4 points: no method applies
  const std::vector<std::size_t> factors{1};
  std::vector<DevPoint> points = compute_deviation(Estimator::oadev, x, 1.0, factors);
  const auto info = fill_confidence(points, Estimator::oadev, x);
  EXPECT_EQ(info[0].noise.method, NoiseIdMethod::none);
  EXPECT_EQ(points[0].alpha, INT_MIN);
  EXPECT_EQ(info[0].edf.method, EdfMethod::ieee952_simple);
  EXPECT_DOUBLE_EQ(points[0].edf, 3.0);
  EXPECT_NE(info[0].note.find("IEEE 952"), std::string::npos) << info[0].note;
  EXPECT_NE(info[0].note.find("--noise-type"), std::string::npos) << info[0].note;
  EXPECT_TRUE(std::isfinite(points[0].ci_high));
}

TEST(FillConfidence, TdevSharesMdevEdf) {
  test::Gaussian gaussian(22);
  const std::vector<double> x = test::power_law_phase(-1, 513, gaussian);
  const std::vector<std::size_t> factors{1, 4, 16};
  std::vector<DevPoint> mdev = compute_deviation(Estimator::mdev, x, 1.0, factors);
  std::vector<DevPoint> tdev = compute_deviation(Estimator::tdev, x, 1.0, factors);
  fill_confidence(mdev, Estimator::mdev, x);
  fill_confidence(tdev, Estimator::tdev, x);
  for (std::size_t i = 0; i < factors.size(); ++i) {
    EXPECT_EQ(tdev[i].alpha, mdev[i].alpha);
    EXPECT_DOUBLE_EQ(tdev[i].edf, mdev[i].edf);
    EXPECT_NEAR(tdev[i].ci_low / tdev[i].dev, mdev[i].ci_low / mdev[i].dev, 1e-12);
  }
}

}  // namespace
}  // namespace imunoise
