// Fusion of simulated recordings, end to end: four TG-100 gyros through the
// tetrahedral axes under a constant body rate. The fused axes' mean is the body rate and their
// fitted N, B, K are the predicted 0.866 N, 0.866 B, 0.866 K.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "imunoise/allan.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "redundant/redundant_test_support.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;
using namespace imunoise::redundant_test;

const std::array<double, 3> kBodyRate{0.1 * kDeg, -0.2 * kDeg, 0.3 * kDeg};

TEST(RedundantFusion, NoiseFreeRecordsGiveTheBodyRateAndZeroParity) {
  const Geometry g = make_geometry("cone:7:40");
  const Analysis a = analyze_unit(g);
  sim::NoiseModel silent;
  silent.bias_unit = 0.0;
  // A time-varying rotation: the fusion is exact for any body rate, the parity ignores it.
  auto w = [](double t) { return std::array<double, 3>{std::sin(t), 0.5 * std::cos(3 * t), 0.2 + 0.01 * t}; };
  std::vector<std::vector<double>> rec(g.size(), std::vector<double>(1000));
  for (std::size_t t = 0; t < 1000; ++t) {
    const auto wt = w(0.01 * static_cast<double>(t));
    for (std::size_t i = 0; i < g.size(); ++i) rec[i][t] = g.axes[i][0] * wt[0] + g.axes[i][1] * wt[1] + g.axes[i][2] * wt[2];
  }
  const FusedRecord f = fuse_records(a, spans_of(rec), 100.0);
  ASSERT_EQ(f.parity_rad_s.size(), 4u);
  for (std::size_t t = 0; t < 1000; ++t) {
    const auto wt = w(0.01 * static_cast<double>(t));
    for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(f.axes_rad_s[j][t], wt[j], 1e-14);
    for (const auto& p : f.parity_rad_s) EXPECT_NEAR(p[t], 0.0, 1e-14);
  }
}

TEST(RedundantFusion, ResultDoesNotDependOnThreadsAndMatchesTheMatrixProduct) {
  const Geometry g = make_geometry("dodeca");
  const Analysis a = analyze_unit(g);
  const auto rec = simulate_unit(g, tg100(false), 100.0, 37.13, 3, [](double) { return kBodyRate; });
  const FusedRecord one = fuse_records(a, spans_of(rec), 100.0);
  FusionOptions o;
  o.threads = 3;
  const FusedRecord three = fuse_records(a, spans_of(rec), 100.0, o);
  EXPECT_EQ(one.axes_rad_s, three.axes_rad_s);
  EXPECT_EQ(one.parity_rad_s, three.parity_rad_s);
  for (std::size_t t = 0; t < rec[0].size(); t += 97) {
    for (std::size_t j = 0; j < 3; ++j) {
      double v = 0;
      for (std::size_t i = 0; i < g.size(); ++i) v += a.fusion(j, i) * rec[i][t];
      EXPECT_NEAR(one.axes_rad_s[j][t], v, 1e-15);
    }
  }
}

TEST(RedundantFusion, BadRecordsAreRefused) {
  const Analysis a = analyze_unit(make_geometry("tetra"));
  std::vector<std::vector<double>> rec(3, std::vector<double>(10, 0.0));
  EXPECT_THROW(fuse_records(a, spans_of(rec), 100.0), InputError);
  rec.emplace_back(9, 0.0);
  EXPECT_THROW(fuse_records(a, spans_of(rec), 100.0), InputError);  // lengths differ
  rec.back().resize(10);
  EXPECT_THROW(fuse_records(a, spans_of(rec), 0.0), InputError);
  FusionOptions o;
  o.detect = true;  // no models
  EXPECT_THROW(fuse_records(a, spans_of(rec), 100.0, o), InputError);
}

// Acceptance: 6 h at 200 Hz, the paper's record length, fixed seed. The fit's N has a relative
// standard error of ~0.4% on such records (docs/fit.md: wls N RMSE 0.4 %), so 3% is > 7 sigma;
// B and K are checked against the fit's own 95% intervals.
TEST(SlowRedundantFusion, TetraAcceptanceFusedNoiseIsThePredictedFraction) {
  const double rate_hz = 200.0, duration_s = 6 * 3600.0;
  const Geometry g = make_geometry("tetra");
  const std::vector<SensorModel> truth(4, truth_model(tg100()));
  const Analysis a = analyze_unit(g, truth);
  const auto rec = simulate_unit(g, tg100(), rate_hz, duration_s, 2026, [](double) { return kBodyRate; });
  FusionOptions o;
  o.threads = 2;
  const FusedRecord f = fuse_records(a, spans_of(rec), rate_hz, o);
  const double gain = std::sqrt(0.75);
  for (std::size_t j = 0; j < 3; ++j) {
    const auto& x = f.axes_rad_s[j];
    // Mean: the standard deviation of a record mean of N, K and flicker noise is
    // sqrt(N^2/T + K^2 T/3 + c B^2) with c < 2 for 1/f noise cut at the record length; 5 sd.
    const double nf = gain * kN * kDeg, bf = gain * kB * kDeg, kf = gain * kK * kDeg;
    const double sd = std::sqrt(nf * nf / duration_s + kf * kf * duration_s / 3 + 2 * bf * bf);
    EXPECT_NEAR(compensated_mean(x), kBodyRate[j], 5 * sd) << "axis " << j;
    EXPECT_LT(5 * sd, 0.1 * std::abs(kBodyRate[j]));  // the check can see a wrong fusion
    // Fit of the fused axis, as `imunoise fit` does.
    const double tau0 = 1.0 / rate_hz;
    const auto phase = phase_from_rate(x, tau0, compensated_mean(x));
    const auto factors = estimator_averaging_factors(Estimator::oadev, parse_tau_grid("octave"), rate_hz, phase.size());
    const auto points = oadev(phase, tau0, factors);
    const fit::FitResult r = fit::fit_allan(points, phase.size(), tau0, fit::FitOptions{});
    const auto& c = r.coefficients;
    const auto& pred = (*a.axes)[j];
    std::printf("axis %zu: N %.5g (pred %.5g, %+.2f%%)  B %.4g [%.4g, %.4g] pred %.4g  K %.4g [%.4g, %.4g] pred %.4g\n", j,
                c.random_walk.value / kDeg, pred.random_walk.value / kDeg,
                100 * (c.random_walk.value / pred.random_walk.value - 1), c.bias_instability.value / kDeg,
                c.bias_instability.ci_low / kDeg, c.bias_instability.ci_high / kDeg, pred.bias_instability.value / kDeg,
                c.rate_random_walk.value / kDeg, c.rate_random_walk.ci_low / kDeg, c.rate_random_walk.ci_high / kDeg,
                pred.rate_random_walk.value / kDeg);
    EXPECT_NEAR(pred.random_walk.value, gain * kN * kDeg, 1e-15);
    EXPECT_NEAR(c.random_walk.value / pred.random_walk.value, 1.0, 0.03);
    EXPECT_LE(c.bias_instability.ci_low, pred.bias_instability.value);
    EXPECT_GE(c.bias_instability.ci_high, pred.bias_instability.value);
    EXPECT_LE(c.rate_random_walk.identified ? c.rate_random_walk.ci_low : 0.0, pred.rate_random_walk.value);
    EXPECT_GE(c.rate_random_walk.ci_high, pred.rate_random_walk.value);
  }
}

}  // namespace
