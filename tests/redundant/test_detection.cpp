// Fault detection, end to end: a step fault on one of six cone sensors is
// detected within seconds and isolated; the same records without it raise no alarm; the
// empirical false-alarm rate over many clean simulated hours matches the configured one.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "imunoise/redundant/detection.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "redundant/redundant_test_support.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;
using namespace imunoise::redundant_test;

// A manoeuvring body: the parity must not see it.
std::array<double, 3> manoeuvre(double t) {
  return {0.3 * std::sin(0.5 * t), -0.2 + 0.1 * std::cos(0.2 * t), 0.05 * t / 600.0};
}

DetectionResult detect(const Geometry& g, const std::vector<std::vector<double>>& rec, double rate_hz,
                       const DetectionOptions& o, const sim::NoiseModel& model) {
  const std::vector<SensorModel> truth(g.size(), truth_model(model));
  FaultDetector d(g, truth, rate_hz, o);
  // In uneven chunks: the result must not depend on them (blocks straddle chunks).
  std::size_t t = 0, step = 777;
  while (t < rec[0].size()) {
    const std::size_t len = std::min(step, rec[0].size() - t);
    std::vector<std::span<const double>> chunk;
    for (const auto& r : rec) chunk.emplace_back(r.data() + t, len);
    d.push(chunk);
    t += len;
    step = step * 7 % 1031 + 1;
  }
  return d.result();
}

TEST(RedundantDetection, StepFaultOnOneOfSixConeSensorsIsDetectedAndIsolated) {
  const double rate_hz = 200.0, duration_s = 600.0, onset_s = 300.37;
  const Geometry g = make_geometry("cone:6:54.7356");
  auto rec = simulate_unit(g, tg100(), rate_hz, duration_s, 11, manoeuvre);
  const DetectionOptions o;  // 1 s window, 60 s reference, 0.01 false alarms per hour
  const DetectionResult clean = detect(g, rec, rate_hz, o, tg100());
  EXPECT_EQ(clean.alarms, 0u);
  EXPECT_TRUE(clean.faults.empty());
  EXPECT_EQ(clean.tests, static_cast<std::size_t>(duration_s) - 60u);

  const std::vector<SensorModel> truth(6, truth_model(tg100()));
  AnalysisOptions ao;
  const Analysis a = analyze_unit(g, truth, ao);
  // A step of 5 minimum detectable faults on sensor 3.
  const double step = 5 * a.min_detectable_fault_rad_s[2];
  std::printf("MDF sensor 3: %.4g deg/s; step %.4g deg/s\n", a.min_detectable_fault_rad_s[2] / kDeg, step / kDeg);
  for (std::size_t t = static_cast<std::size_t>(onset_s * rate_hz); t < rec[2].size(); ++t) rec[2][t] += step;
  const DetectionResult r = detect(g, rec, rate_hz, o, tg100());
  for (const auto& e : r.faults) {
    std::printf("fault: sensor %zu onset %.3f s detected %.3f s T %.1f (max %.1f) > %.1f, %zu alarms\n", e.sensor + 1,
                e.onset_s, e.detected_s, e.statistic, e.max_statistic, e.threshold, e.alarms);
  }
  ASSERT_EQ(r.faults.size(), 1u);
  const auto& f = r.faults[0];
  std::printf("fault: sensor %zu onset %.3f s detected %.3f s T %.1f > %.1f\n", f.sensor + 1, f.onset_s,
              f.detected_s, f.statistic, f.threshold);
  EXPECT_EQ(f.sensor, 2u);
  EXPECT_EQ(f.candidates, std::vector<std::size_t>{2});
  EXPECT_TRUE(f.isolated);
  EXPECT_LE(f.detected_s - onset_s, 2.0);  // within two windows
  EXPECT_NEAR(f.onset_s, onset_s, 0.1);    // one block is 0.05 s
  EXPECT_GT(f.statistic, f.threshold);
  ASSERT_EQ(r.excluded.size(), 1u);
  EXPECT_EQ(r.excluded[0], 2u);
}

TEST(RedundantDetection, SecondFaultOnAnotherSensorIsIsolatedToo) {
  // After the first isolated fault the sensor leaves the test; a second step 20 s later on
  // another sensor (while the reference still holds the first) is found and isolated.
  const double rate_hz = 100.0;
  const Geometry g = make_geometry("cone:6:54.7356");
  auto rec = simulate_unit(g, tg100(), rate_hz, 300.0, 12, manoeuvre);
  for (std::size_t t = 100 * 100; t < rec[0].size(); ++t) rec[0][t] += 0.06 * kDeg;
  for (std::size_t t = 120 * 100; t < rec[4].size(); ++t) rec[4][t] -= 0.06 * kDeg;
  const DetectionResult r = detect(g, rec, rate_hz, DetectionOptions{}, tg100());
  ASSERT_EQ(r.faults.size(), 2u);
  EXPECT_EQ(r.faults[0].sensor, 0u);
  EXPECT_EQ(r.faults[1].sensor, 4u);
  EXPECT_NEAR(r.faults[0].onset_s, 100.0, 0.1);
  EXPECT_NEAR(r.faults[1].onset_s, 120.0, 0.1);
  EXPECT_TRUE(r.faults[1].isolated);  // five sensors left: still isolable
  EXPECT_LT(r.faults[1].threshold, r.faults[0].threshold);  // chi2_2 instead of chi2_3
}

TEST(RedundantDetection, FourSensorsDetectButDoNotIsolate) {
  const double rate_hz = 100.0;
  const Geometry g = make_geometry("tetra");
  auto rec = simulate_unit(g, tg100(), rate_hz, 300.0, 5, manoeuvre);
  for (std::size_t t = 200 * 100; t < rec[1].size(); ++t) rec[1][t] += 0.05 * kDeg;
  const DetectionResult r = detect(g, rec, rate_hz, DetectionOptions{}, tg100());
  ASSERT_EQ(r.faults.size(), 1u);
  EXPECT_FALSE(r.faults[0].isolated);
  EXPECT_NEAR(r.faults[0].onset_s, 200.0, 0.1);
}

// The alarm count of n tests at per-test probability p is close to binomial (consecutive tests
// share part of the reference, which correlates them only weakly: reference 60 windows): its
// mean n p holds exactly for Gaussian noise; the band is 4 binomial standard deviations.
void expect_rate(const DetectionResult& r, double configured_per_hour, double hours) {
  const double n = static_cast<double>(r.tests);
  const double p = r.design.per_test_probability;
  const double expected = n * p;
  const double sd = std::sqrt(n * p * (1 - p));
  std::printf("%.0f tests, p %.3g: %zu alarms, expected %.1f +- %.1f; empirical rate %.4g/h vs %.4g/h\n", n, p,
              r.alarms, expected, sd, static_cast<double>(r.alarms) / hours, configured_per_hour);
  EXPECT_NEAR(static_cast<double>(r.alarms), expected, 4 * sd);
}

TEST(RedundantDetection, EmpiricalFalseAlarmRateMatchesTheConfiguredRate) {
  // 20 clean hours of a six-gyro cone, white noise (the model the test statistic is exact for).
  const double rate_hz = 50.0, hours = 20.0;
  const Geometry g = make_geometry("cone:6:54.7356");
  const auto rec = simulate_unit(g, tg100(false), rate_hz, hours * 3600, 99, manoeuvre);
  DetectionOptions o;
  o.window_s = 0.5;
  o.reference_s = 30.0;
  o.exclude_isolated = false;  // count raw alarms: a false alarm must not remove a sensor here
  for (double per_hour : {72.0, 7.2}) {  // per-test probabilities 1e-2 and 1e-3
    o.false_alarm_per_hour = per_hour;
    expect_rate(detect(g, rec, rate_hz, o, tg100(false)), per_hour, hours);
  }
}

TEST(SlowRedundantDetection, FalseAlarmRateWithBiasInstabilityAndRateRandomWalk) {
  // The same with the TG-100's flicker and rate random walk, whose share of the window-minus-
  // reference variance (~40% here) the design computes from the model.
  const double rate_hz = 50.0, hours = 20.0;
  const Geometry g = make_geometry("cone:6:54.7356");
  const auto rec = simulate_unit(g, tg100(), rate_hz, hours * 3600, 98, manoeuvre);
  DetectionOptions o;
  o.window_s = 0.5;
  o.reference_s = 30.0;
  o.exclude_isolated = false;  // count raw alarms: a false alarm must not remove a sensor here
  o.false_alarm_per_hour = 72.0;
  expect_rate(detect(g, rec, rate_hz, o, tg100()), 72.0, hours);
}

TEST(RedundantDetection, MinimumDetectableFaultIsDetectedWithTheStatedProbability) {
  // Steps of exactly the MDF at detection probability 0.5, each in a fresh stretch of clean
  // data: about half the windows that hold the step fully must alarm.
  const double rate_hz = 50.0;
  const Geometry g = make_geometry("cone:6:54.7356");
  DetectionOptions o;
  o.window_s = 1.0;
  o.reference_s = 20.0;
  o.detection_probability = 0.5;
  o.exclude_isolated = false;
  o.false_alarm_per_hour = 3.6;  // per-test 1e-3
  const std::vector<SensorModel> truth(6, truth_model(tg100(false)));
  AnalysisOptions ao;
  ao.detection = o;
  const Analysis a = analyze_unit(g, truth, ao);
  auto rec = simulate_unit(g, tg100(false), rate_hz, 400 * 21.0 + 20.0, 77, manoeuvre);
  // Every 21 s a one-window pulse of MDF size on sensor 1 starting at a window boundary, so
  // that the test window sees it whole and the reference before it is clean.
  const std::size_t per = 21 * 50;
  for (std::size_t k = 1; k <= 400; ++k) {
    const std::size_t t0 = k * per;
    for (std::size_t t = t0; t < t0 + 50 && t < rec[0].size(); ++t) rec[0][t] += a.min_detectable_fault_rad_s[0];
  }
  const DetectionResult r = detect(g, rec, rate_hz, o, tg100(false));
  // Alarms from the pulses (the window after a pulse has it in its reference only, lowering T).
  const double background = static_cast<double>(r.tests - 400) * r.design.per_test_probability;
  const double hits = static_cast<double>(r.alarms) - background;
  std::printf("pulses 400: alarms %zu (background %.1f): detection fraction %.3f\n", r.alarms, background, hits / 400);
  EXPECT_NEAR(hits / 400.0, 0.5, 4 * std::sqrt(0.25 / 400) + 0.01);
}

TEST(RedundantDetection, BadDetectionInputIsRefused) {
  const Geometry g = make_geometry("3+1");
  const std::vector<SensorModel> truth(4, truth_model(tg100()));
  DetectionOptions o;
  o.false_alarm_per_hour = -1;
  EXPECT_THROW(FaultDetector(g, truth, 100.0, o), InputError);
  o = DetectionOptions{};
  o.reference_s = 0.5;
  EXPECT_THROW(FaultDetector(g, truth, 100.0, o), InputError);
  EXPECT_THROW(FaultDetector(make_geometry("cone:3:50"), std::vector<SensorModel>(3, truth[0]), 100.0, DetectionOptions{}),
               InputError);
  EXPECT_THROW(FaultDetector(g, std::vector<SensorModel>(2, truth[0]), 100.0, DetectionOptions{}), InputError);
  EXPECT_THROW(FaultDetector(g, truth, 0.0, DetectionOptions{}), InputError);
  std::vector<SensorModel> silent(4);
  EXPECT_THROW(FaultDetector(g, silent, 100.0, DetectionOptions{}), InputError);
}

}  // namespace
