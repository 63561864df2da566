// The simulated unit under motion (redundant/unit_simulation.hpp): the sample-averaged motion
// against numerical integration, the geometry, scale-factor and misalignment algebra on
// noise-free sensors, and noise that grows with the sensed rate measured by the in-motion
// analysis.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "imunoise/error.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/redundant/unit_simulation.hpp"
#include "redundant/redundant_test_support.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;
using imunoise::redundant_test::kDeg;
using imunoise::redundant_test::spans_of;

MotionProfile busy() {
  MotionProfile p = tumble_profile(200 * kDeg);
  p.constant_rad_s = {0.1, -0.2, 0.05};
  RotationLine vib;  // a vibration line at 40 Hz on two axes
  vib.frequency_hz = 40.0;
  vib.amplitude_rad_s = {0.3, 0.0, 0.2};
  vib.phase_rad = {0.4, 0.0, -1.1};
  p.lines.push_back(vib);
  return p;
}

TEST(RedundantUnitSimulation, SampleMeanOfTheMotionIsTheIntegral) {
  const MotionProfile p = busy();
  for (double t0 : {0.0, 0.37, 12.345}) {
    const double dt = 0.01;
    const auto w = p.mean_rate(t0, dt);
    // Simpson's rule on 2000 intervals.
    std::array<double, 3> s{};
    const int k = 2000;
    for (int j = 0; j <= k; ++j) {
      const double t = t0 + dt * j / k;
      const double c = (j == 0 || j == k) ? 1.0 : (j % 2 ? 4.0 : 2.0);
      std::array<double, 3> v = p.constant_rad_s;
      for (const auto& l : p.lines) {
        for (int a = 0; a < 3; ++a) v[a] += l.amplitude_rad_s[a] * std::sin(2 * std::numbers::pi * l.frequency_hz * t + l.phase_rad[a]);
      }
      for (int a = 0; a < 3; ++a) s[a] += c * v[a];
    }
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(w[a], s[a] / (3.0 * k), 1e-12) << t0 << " " << a;
  }
}

TEST(RedundantUnitSimulation, NoiseFreeSensorsFollowTheirAxesScaleAndMisalignment) {
  const Geometry g = make_geometry("dodeca");
  std::vector<UnitSensor> sensors(6);
  sensors[0].scale_factor_ppm = 1000.0;
  sensors[1].misalignment_rad = {1e-3, -2e-3, 0.5e-3};
  sensors[2].misalignment_rad = {0.01 * g.axes[2][0], 0.01 * g.axes[2][1], 0.01 * g.axes[2][2]};  // along the axis: no tilt
  const MotionProfile p = busy();
  const auto rec = simulate_unit(g, sensors, p, 200.0, 5.0, 1);
  ASSERT_EQ(rec.size(), 6u);
  ASSERT_EQ(rec[0].size(), 1000u);
  const Matrix v = parity_of(measurement_matrix(g));
  for (std::size_t t = 0; t < 1000; t += 37) {
    const auto w = p.mean_rate(static_cast<double>(t) * (1.0 / 200.0), 1.0 / 200.0);
    auto dot = [&](const Axis& h) { return h[0] * w[0] + h[1] * w[1] + h[2] * w[2]; };
    EXPECT_NEAR(rec[0][t], 1.001 * dot(g.axes[0]), 1e-14);
    const auto& h1 = g.axes[1];
    const auto& d = sensors[1].misalignment_rad;
    const double along = d[0] * h1[0] + d[1] * h1[1] + d[2] * h1[2];
    const Axis tilted{h1[0] + d[0] - along * h1[0], h1[1] + d[1] - along * h1[1], h1[2] + d[2] - along * h1[2]};
    EXPECT_NEAR(rec[1][t], dot(tilted), 1e-14);
    EXPECT_NEAR(rec[2][t], dot(g.axes[2]), 1e-14);
    for (std::size_t i = 3; i < 6; ++i) EXPECT_NEAR(rec[i][t], dot(g.axes[i]), 1e-14);
  }
  // Without errors the parity of the motion is zero to rounding.
  std::vector<UnitSensor> perfect(6);
  const auto clean = simulate_unit(g, perfect, p, 200.0, 5.0, 1);
  for (std::size_t t = 0; t < 1000; t += 13) {
    for (std::size_t j = 0; j < v.rows; ++j) {
      double s = 0;
      for (std::size_t i = 0; i < 6; ++i) s += v(j, i) * clean[i][t];
      EXPECT_NEAR(s, 0.0, 1e-14);
    }
  }
}

TEST(RedundantUnitSimulation, MotionDependentNoiseIsWhatTheInMotionAnalysisMeasures) {
  // White noise N0 at rest plus c |h . w| while turning: in motion each sensor's Allan variance
  // is (N0^2 + c^2 <(h . w)^2>) / tau (the time average of the modulated density).
  const Geometry g = make_geometry("dodeca");
  const double n0 = 1e-3 * kDeg;
  const MotionProfile p = tumble_profile(200 * kDeg);
  std::vector<UnitSensor> sensors(6);
  for (std::size_t i = 0; i < 6; ++i) {
    sensors[i].noise.n_unit_sqrt_s = n0;
    sensors[i].motion_noise_sqrt_s = (i % 2 ? 1.0 : 0.3) * 7e-6;
  }
  const double rate = 100.0;
  const double duration = 300.0;
  const auto rec = simulate_unit(g, sensors, p, rate, duration, 3);
  const auto r = in_motion_noise(g, spans_of(rec), rate);
  ASSERT_TRUE(r.identifiability.per_sensor);
  const std::size_t len = rec[0].size();
  for (std::size_t i = 0; i < 6; ++i) {
    double mean_sq = 0;
    for (std::size_t t = 0; t < len; ++t) {
      const auto w = p.mean_rate(static_cast<double>(t) * (1.0 / rate), 1.0 / rate);
      const auto& h = g.axes[i];
      const double s = h[0] * w[0] + h[1] * w[1] + h[2] * w[2];
      mean_sq += s * s / static_cast<double>(len);
    }
    const double c = sensors[i].motion_noise_sqrt_s;
    const double density = std::sqrt(n0 * n0 + c * c * mean_sq);
    for (std::size_t q = 0; q < 4; ++q) {
      const auto& pt = r.sensors[i][q];
      // Within 4 standard errors of the estimate (its own EDF).
      EXPECT_NEAR(pt.dev / (density / std::sqrt(pt.tau_s)), 1.0, 4.0 / std::sqrt(2.0 * pt.edf)) << "sensor " << i + 1 << " tau " << pt.tau_s;
    }
    // The odd sensors are visibly noisier in motion than at rest (density / N0 ~ 1.4).
    if (i % 2) {
      EXPECT_GT(r.sensors[i][0].dev / (n0 / std::sqrt(0.01)), 1.3);
    }
  }
}

TEST(RedundantUnitSimulation, RefusesBadInput) {
  const Geometry g = make_geometry("tetra");
  std::vector<UnitSensor> three(3);
  EXPECT_THROW(simulate_unit(g, three, {}, 100.0, 1.0, 1), InputError);
  std::vector<UnitSensor> four(4);
  MotionProfile fast;
  RotationLine l;
  l.frequency_hz = 60.0;
  fast.lines.push_back(l);
  EXPECT_THROW(simulate_unit(g, four, fast, 100.0, 1.0, 1), InputError);
}

}  // namespace
