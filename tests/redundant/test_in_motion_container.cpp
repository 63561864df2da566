// The in-motion analysis of a unit whose sensors sit in one container (a PX4 log's sensor_gyro
// instances, each on its own clock), the timing leakage of instances sampled at different
// instants, and the gyros' g-sensitivity on the specific force. Simulated units with known truth
// (redundant::simulate_unit, fixed seeds); the log is written by tests/redundant/ulog_unit_writer.hpp
// from the format specification.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/redundant/unit_simulation.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/study/in_motion.hpp"
#include "imunoise/study/in_motion_container.hpp"
#include "redundant/redundant_test_support.hpp"
#include "redundant/ulog_unit_writer.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;
using imunoise::test::run_cli;
using imunoise::test::TempDir;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kRate = 200.0;

// N_i = (0.8 + 0.1 i) 1e-3 deg/sqrt(s), white noise only (the tests here are about leakage).
std::vector<UnitSensor> white_sensors(std::size_t n) {
  std::vector<UnitSensor> s(n);
  for (std::size_t i = 0; i < n; ++i) s[i].noise.n_unit_sqrt_s = (0.8e-3 + 0.1e-3 * static_cast<double>(i)) * kDeg;
  return s;
}


// The fitted N of every sensor over its truth.
std::vector<double> n_ratios(const study::InMotionUnit& unit, const std::vector<UnitSensor>& truth) {
  std::vector<double> out;
  for (std::size_t i = 0; i < unit.sensors.size(); ++i) {
    const auto& s = unit.sensors[i];
    EXPECT_TRUE(s.fit.has_value()) << "sensor " << i + 1 << ": " << s.reason;
    out.push_back(s.fit ? s.fit->coefficients.random_walk.value / truth[i].noise.n_unit_sqrt_s : 0.0);
  }
  return out;
}

// The adev of sensor i's in-motion curve at tau nearest `tau_s` over its white-noise truth.
double adev_ratio(const InMotionResult& r, std::size_t i, double n_rad_sqrt_s, double tau_s) {
  const auto& curve = r.sensors.at(i);
  std::size_t best = 0;
  for (std::size_t q = 1; q < curve.size(); ++q) {
    if (std::abs(std::log(curve[q].tau_s / tau_s)) < std::abs(std::log(curve[best].tau_s / tau_s))) best = q;
  }
  return curve[best].dev / (n_rad_sqrt_s / std::sqrt(curve[best].tau_s));
}

TEST(RedundantInMotionContainer, PairingKeepsEachInstancesOffsetAndRefusesSlipsAndOtherRates) {
  // Three instances at 200 Hz: the second 1.234 ms late and starting 3 samples later, the third
  // 2.0 ms early with 0.1 ms of jitter.
  std::vector<std::vector<double>> t(3);
  for (int q = 0; q < 1000; ++q) t[0].push_back(0.005 * q);
  for (int q = 3; q < 1000; ++q) t[1].push_back(0.005 * q + 1.234e-3);
  for (int q = 0; q < 990; ++q) t[2].push_back(0.005 * q - 2.0e-3 + (q % 10 == 0 ? 1e-4 : 0.0));
  std::vector<std::span<const double>> spans(t.begin(), t.end());
  const std::vector<std::string> names{"g0", "g1", "g2"};
  const auto p = study::pair_instances(spans, names);
  EXPECT_EQ(p.first[0], 3u);
  EXPECT_EQ(p.first[1], 0u);
  EXPECT_EQ(p.first[2], 3u);
  EXPECT_EQ(p.count, 987u);
  EXPECT_NEAR(p.mean_offset_s[1], 1.234e-3, 1e-12);
  EXPECT_NEAR(p.mean_offset_s[2], -2.0e-3 + 1e-5, 1e-7);
  EXPECT_NEAR(p.spread_s[2], 1e-4, 1e-12);
  // A clock 0.05 % fast slips by a whole sample over 2000 samples: refused, naming it.
  std::vector<double> drift;
  for (int q = 0; q < 2000; ++q) drift.push_back(0.005 * q * 1.0005);
  std::vector<double> ref;
  for (int q = 0; q < 2000; ++q) ref.push_back(0.005 * q);
  const std::vector<std::span<const double>> slip{ref, drift};
  try {
    (void)study::pair_instances(slip, names);
    FAIL() << "a slipping clock was paired";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("g1 slips against g0"), std::string::npos) << e.what();
  }
  // Another rate (400 Hz against 200 Hz): refused, naming both and saying why not resampled.
  std::vector<double> fast;
  for (int q = 0; q < 2000; ++q) fast.push_back(0.0025 * q);
  const std::vector<std::span<const double>> rates{ref, fast};
  try {
    (void)study::pair_instances(rates, names);
    FAIL() << "instances at 200 and 400 Hz were paired";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("g1 is sampled at 400 Hz but g0 at 200 Hz"), std::string::npos) << m;
    EXPECT_NE(m.find("never resamples"), std::string::npos) << m;
  }
  // A gap in one instance: refused by the timing check, naming it.
  std::vector<double> gap = ref;
  for (std::size_t q = 1000; q < gap.size(); ++q) gap[q] += 0.05;
  const std::vector<std::span<const double>> gaps{ref, gap};
  try {
    (void)study::pair_instances(gaps, names);
    FAIL() << "an instance with a gap was paired";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("g1"), std::string::npos) << e.what();
  }
}

// Three co-aligned triads under the 200 deg/s tumble, the second sampled 0.25 sample late and
// the third 0.2 early (as instances on their own clocks, paired to the nearest sample). Measured
// over seeds 4242, 999, 17, 23: fitted N 0.957-1.012 of truth (36 fits); with offsets of 0.4 and
// -0.3 sample 0.950-1.023 over seeds 4242 and 999, against 0.994-1.007 without offsets: the
// derivative regressors carry the fused noise, and the part of it the correction injects is
// common to co-aligned sensors, not of the independent-sensor form (docs/redundant.md).
TEST(RedundantInMotionContainer, TimingLeakageOfInstancesOnTheirOwnClocksIsRemoved) {
  const Geometry g = make_geometry("triads:3");
  auto sensors = white_sensors(9);
  for (std::size_t i = 3; i < 6; ++i) sensors[i].time_offset_s = 0.25 / kRate;
  for (std::size_t i = 6; i < 9; ++i) sensors[i].time_offset_s = -0.2 / kRate;
  const auto motion = tumble_profile(200.0 * kDeg);
  const auto rec = simulate_unit(g, sensors, motion, kRate, 600.0, 4242);
  InMotionOptions o;
  o.require_per_sensor = true;
  // Without the timing regression only the curves (the fit of a swamped curve is meaningless).
  std::vector<std::span<const double>> spans(rec.begin(), rec.end());
  const auto without = in_motion_noise(g, spans, kRate, o);
  o.remove_timing_leakage = true;
  const auto with = study::analyze_in_motion(g, redundant_test::as_records(rec, kRate), o, fit::FitOptions{});
  const auto n_with = n_ratios(with, sensors);
  for (std::size_t i = 0; i < 9; ++i) {
    const double before = adev_ratio(without, i, sensors[i].noise.n_unit_sqrt_s, 1.0);
    const double after = adev_ratio(with.result, i, sensors[i].noise.n_unit_sqrt_s, 1.0);
    std::printf("triads:3 sensor %zu: adev(1 s) / truth %.3g without the timing regression, %.4f with; fitted N / "
                "true %.4f; time offset %.4f ms (relative to the unit)\n",
                i + 1, before, after, n_with[i], with.result.leakage.time_offset_ms[i]);
    // Without it the leakage swamps the curves: far above the truth, or (NNLS at its bound) 0.
    EXPECT_TRUE(before > 3.0 || before < 0.3) << "sensor " << i + 1 << ": " << before;
    EXPECT_NEAR(n_with[i], 1.0, 0.05) << "sensor " << i + 1;
  }
  // The minimum-norm offsets: the unit's mean removed (P of co-aligned triads averages each axis
  // over the triads), so instance k shows dt_k - mean(dt) = (0, 1.25, -1) ms - 0.0833 ms.
  const double mean_ms = (0.0 + 1.25 - 1.0) / 3.0;
  for (std::size_t i = 0; i < 9; ++i) {
    const double truth = 1e3 * sensors[i].time_offset_s - mean_ms;
    EXPECT_NEAR(with.result.leakage.time_offset_ms[i], truth, 0.01) << "sensor " << i + 1;
  }
}

// A known g-sensitivity on two gyros of three co-aligned triads, the specific force from a
// tumbling unit at rest (gravity turning in the body) read by three noisy accelerometer triads.
TEST(RedundantInMotionContainer, GSensitivityIsRecoveredWithinItsStandardErrorAndRemoved) {
  const Geometry g = make_geometry("triads:3");
  auto sensors = white_sensors(9);
  const double per_g = kDeg / 3600.0 / study::kStandardGravity_m_s2;  // 1 deg/h/g in rad/s per m/s^2
  sensors[1].g_sensitivity_rad_s_per_m_s2 = {0.0, 0.0, 150.0 * per_g};
  sensors[5].g_sensitivity_rad_s_per_m_s2 = {-80.0 * per_g, 40.0 * per_g, 0.0};
  const auto motion = tumble_profile(100.0 * kDeg);
  const double duration = 600.0;
  const auto rec = simulate_unit(g, sensors, motion, kRate, duration, 777);
  auto force = specific_force(motion, kRate, duration);
  // Accelerometer triads: white noise of 1e-3 m/s^2 per sample on each, averaged.
  {
    sim::SimulationSpec spec;
    spec.rate_hz = kRate;
    spec.duration_s = duration;
    spec.seed = 99;
    for (int c = 0; c < 9; ++c) {
      sim::NoiseModel m;
      m.n_unit_sqrt_s = 1e-3 / std::sqrt(kRate);
      spec.channels.push_back({m, {}, ""});
    }
    sim::Generator gen(spec);
    std::vector<std::vector<double>> noise(9, std::vector<double>(force[0].size()));
    std::vector<std::span<double>> spans(noise.begin(), noise.end());
    gen.generate_planar(spans, 1);
    for (std::size_t c = 0; c < 9; ++c) {
      for (std::size_t t = 0; t < force[0].size(); ++t) force[c % 3][t] += noise[c][t] / 3.0;
    }
  }
  InMotionOptions o;
  o.require_per_sensor = true;
  const auto without = study::analyze_in_motion(g, redundant_test::as_records(rec, kRate), o, fit::FitOptions{});
  const auto with = study::analyze_in_motion(g, redundant_test::as_records(rec, kRate), o, fit::FitOptions{}, force);
  ASSERT_TRUE(with.result.leakage.g_sensitivity_estimated);
  // The visible part: P Gs (P = V^T V; co-aligned triads: each axis minus its mean over the triads).
  std::array<std::array<double, 3>, 9> truth{};
  for (std::size_t i = 0; i < 9; ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      double mean = 0.0;
      for (std::size_t k = 0; k < 3; ++k) mean += sensors[3 * k + i % 3].g_sensitivity_rad_s_per_m_s2[a] / 3.0;
      truth[i][a] = sensors[i].g_sensitivity_rad_s_per_m_s2[a] - mean;
    }
  }
  std::size_t within_2se = 0;
  for (std::size_t i = 0; i < 9; ++i) {
    const auto& est = with.result.leakage.g_sensitivity_rad_s_per_m_s2[i];
    const auto& se = with.result.leakage.g_sensitivity_se_rad_s_per_m_s2[i];
    for (std::size_t a = 0; a < 3; ++a) {
      const double z = (est[a] - truth[i][a]) / se[a];
      within_2se += std::abs(z) < 2 ? 1 : 0;
      EXPECT_LT(std::abs(z), 4.0) << "sensor " << i + 1 << " axis " << a;
      EXPECT_LT(se[a], 2.0 * per_g) << "sensor " << i + 1 << " axis " << a;
    }
    std::printf("g-sensitivity sensor %zu: (%.2f, %.2f, %.2f) +- (%.2f, %.2f, %.2f) deg/h/g, truth (P Gs) (%.2f, "
                "%.2f, %.2f)\n", i + 1, est[0] / per_g, est[1] / per_g, est[2] / per_g, se[0] / per_g, se[1] / per_g,
                se[2] / per_g, truth[i][0] / per_g, truth[i][1] / per_g, truth[i][2] / per_g);
  }
  std::printf("g-sensitivity: %zu of 27 components within 2 standard errors\n", within_2se);
  EXPECT_GE(within_2se, 22u);  // 95 % of 27 is 25.7; 22 is 3.4 binomial sd below
  // Without the specific force the g-sensitivity leaks: sensors 2 and 6 show it at 1-4 s.
  for (std::size_t i : {1u, 5u}) {
    const double before = adev_ratio(without.result, i, sensors[i].noise.n_unit_sqrt_s, 2.0);
    const double after = adev_ratio(with.result, i, sensors[i].noise.n_unit_sqrt_s, 2.0);
    std::printf("g-sensitivity sensor %zu: adev(2 s) / truth %.3g without the specific force, %.4f with\n", i + 1,
                before, after);
    EXPECT_GT(before, 2.0) << "sensor " << i + 1;
  }
  const auto n_with = n_ratios(with, sensors);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(n_with[i], 1.0, 0.05) << "sensor " << i + 1;
}

// A PX4 log of three IMUs (sensor_gyro and sensor_accel, multi_id 0 1 2, each instance on its own
// clock): the unit read from the one file, each sensor's N recovered as from separate files.
struct LoggedUnit {
  std::vector<UnitSensor> sensors;
  std::string path;
};

LoggedUnit write_log(const TempDir& dir, double duration_s, bool third_at_other_rate = false) {
  LoggedUnit out;
  const Geometry g = make_geometry("triads:3");
  out.sensors = white_sensors(9);
  const double offset_us[3] = {0.0, 1234.0, -800.0};
  for (std::size_t i = 0; i < 9; ++i) out.sensors[i].time_offset_s = offset_us[i / 3] * 1e-6;
  out.sensors[4].g_sensitivity_rad_s_per_m_s2 = {0.0, 0.0, 120.0 * kDeg / 3600.0 / study::kStandardGravity_m_s2};
  const auto motion = tumble_profile(150.0 * kDeg);
  const auto rec = simulate_unit(g, out.sensors, motion, kRate, duration_s, 31337);
  const auto force = specific_force(motion, kRate, duration_s);
  imunoise::redundant_test::UlogWriter log;
  for (std::uint8_t k = 0; k < 3; ++k) {
    imunoise::redundant_test::UlogInstance gyro;
    imunoise::redundant_test::UlogInstance accel;
    const bool other = third_at_other_rate && k == 2;
    for (std::size_t q = 0; q < rec[0].size(); ++q) {
      const double t_us = 5'000'000.0 + (other ? 5010.0 : 5000.0) * static_cast<double>(q) + offset_us[k];
      gyro.timestamp_us.push_back(static_cast<std::uint64_t>(std::llround(t_us)));
      accel.timestamp_us.push_back(static_cast<std::uint64_t>(std::llround(t_us + 37.0)));
      for (std::size_t a = 0; a < 3; ++a) {
        gyro.xyz[a].push_back(rec[3 * k + a][q]);
        accel.xyz[a].push_back(force[a][q]);
      }
    }
    log.add("sensor_gyro", k, gyro);
    log.add("sensor_accel", k, accel);
  }
  out.path = dir.file(third_at_other_rate ? "other_rate.ulg" : "unit.ulg");
  log.write(out.path);
  return out;
}

TEST(RedundantInMotionContainer, PX4LogOfThreeImusGivesEachSensorsNoise) {
  TempDir dir;
  const auto logged = write_log(dir, 600.0);
  load::LoadOptions lo;
  lo.file = logged.path;
  const std::vector<std::string> topics{"sensor_gyro"};
  const std::vector<std::string> accel_topics{"sensor_accel"};
  auto cu = study::read_container_unit(lo, topics, accel_topics);
  ASSERT_EQ(cu.gyros.size(), 9u);
  EXPECT_EQ(cu.gyros[3].channel, "gyro1_x");
  EXPECT_EQ(cu.accel_instances, 3u);
  EXPECT_NEAR(cu.instance_offset_s[1], 1.234e-3, 1e-9);
  EXPECT_NEAR(cu.instance_offset_s[2], -0.8e-3, 1e-9);
  InMotionOptions o;
  o.require_per_sensor = true;
  o.remove_timing_leakage = true;
  const auto unit = study::analyze_in_motion(make_geometry("triads:3"), std::move(cu.gyros), o, fit::FitOptions{},
                                             cu.specific_force_m_s2);
  const auto n = n_ratios(unit, logged.sensors);
  for (std::size_t i = 0; i < 9; ++i) {
    std::printf("PX4 log sensor %zu (%s): fitted N / true %.4f\n", i + 1, unit.sensors[i].record.channel.c_str(), n[i]);
    EXPECT_NEAR(n[i], 1.0, 0.05) << "sensor " << i + 1;
  }
  // Sensor 5 (gyro1_y)'s 120 deg/h/g on z: P Gs gives it 2/3 of it, its co-aligned partners -1/3.
  const double per_g = kDeg / 3600.0 / study::kStandardGravity_m_s2;
  const auto& lk = unit.result.leakage;
  std::printf("PX4 log g-sensitivity z: sensor 2 %.2f, 5 %.2f, 8 %.2f deg/h/g (+- %.2f)\n",
              lk.g_sensitivity_rad_s_per_m_s2[1][2] / per_g, lk.g_sensitivity_rad_s_per_m_s2[4][2] / per_g,
              lk.g_sensitivity_rad_s_per_m_s2[7][2] / per_g, lk.g_sensitivity_se_rad_s_per_m_s2[4][2] / per_g);
  EXPECT_NEAR(lk.g_sensitivity_rad_s_per_m_s2[4][2] / per_g, 80.0, 4 * lk.g_sensitivity_se_rad_s_per_m_s2[4][2] / per_g);
  EXPECT_NEAR(lk.g_sensitivity_rad_s_per_m_s2[1][2] / per_g, -40.0, 4 * lk.g_sensitivity_se_rad_s_per_m_s2[1][2] / per_g);
}

TEST(RedundantInMotionContainer, CommandLineReadsTheUnitFromOnePX4Log) {
  TempDir dir;
  const auto logged = write_log(dir, 300.0);
  const auto r = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", logged.path, "--topic", "sensor_gyro",
                          "--accel-topic", "sensor_accel", "--per-sensor"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  const auto& im = doc.at("in_motion");
  ASSERT_EQ(im.at("sensors").size(), 9u);
  EXPECT_TRUE(im.at("leakage").at("timing").get<bool>());
  EXPECT_TRUE(im.at("leakage").at("g_sensitivity").get<bool>());
  EXPECT_EQ(im.at("unit").get<std::string>(), "rad/s");
  for (std::size_t i = 0; i < 9; ++i) {
    const auto& s = im.at("sensors")[i];
    EXPECT_NE(s.at("source").get<std::string>().find(fmt::format("gyro{}_{}", i / 3, "xyz"[i % 3])), std::string::npos);
    const double n = s.at("fit").at("terms").at("N").at("value").get<double>();
    EXPECT_NEAR(n / logged.sensors[i].noise.n_unit_sqrt_s, 1.0, 0.05) << "sensor " << i + 1;
    EXPECT_EQ(s.at("leakage").at("g_sensitivity").at("unit").get<std::string>(), "deg/h/g");
  }
  EXPECT_NE(r.err.find("paired sample by sample"), std::string::npos) << r.err;
  // Two instances for nine axes, another rate, a topic without gyros: exit 1 naming the cause.
  const auto wrong = run_cli({"redundant", "--geometry", "dodeca", "--in-motion", logged.path, "--topic", "sensor_gyro"});
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("9 recordings for the 6 sensors"), std::string::npos) << wrong.err;
  const auto other = write_log(dir, 20.0, true);
  const auto rate = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", other.path, "--topic", "sensor_gyro"});
  EXPECT_EQ(rate.exit_code, 1);
  EXPECT_NE(rate.err.find("topic sensor_gyro instance gyro2 is sampled at"), std::string::npos) << rate.err;
  const auto accel = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", logged.path, "--topic",
                              "sensor_accel"});
  EXPECT_EQ(accel.exit_code, 1);
  EXPECT_NE(accel.err.find("no gyro channels"), std::string::npos) << accel.err;
  const auto column = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", logged.path, "--topic",
                               "sensor_gyro", "--column", "gyro0_x"});
  EXPECT_EQ(column.exit_code, 1);
  EXPECT_NE(column.err.find("do not apply to a container holding the whole unit"), std::string::npos) << column.err;
  const auto rate_given = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", logged.path, "--topic",
                                   "sensor_gyro", "--rate", "100"});
  EXPECT_EQ(rate_given.exit_code, 1);
  EXPECT_NE(rate_given.err.find("--rate 100 Hz disagrees"), std::string::npos) << rate_given.err;
}

TEST(RedundantInMotionContainer, RealPX4LogIsReadAndItsUnsuitableInstancesRefusedWithTheReason) {
  // pyulog's sample flight log (tests/data/ulog/README.md): three IMUs, but vehicle_imu logged at
  // 2 Hz, instance 0's median interval 0.3 % off the others': refused, naming the instances.
  const std::string log = std::string(IMUNOISE_TEST_DATA_DIR) + "/ulog/sample_log_small.ulg";
  const auto r = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", log, "--topic", "vehicle_imu"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("topic vehicle_imu instance gyro1 is sampled at 2 Hz but"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("instance gyro0 at 2.0057"), std::string::npos) << r.err;
  const auto few = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", log, "--topic", "sensor_gyro"});
  EXPECT_EQ(few.exit_code, 1);
  EXPECT_NE(few.err.find("overlap by"), std::string::npos) << few.err;
}

TEST(RedundantInMotionContainer, RosBagWithThreeImuTopicsGivesEachSensorsNoise) {
  // Three sensor_msgs/Imu topics written by the real rosbag library (tests/redundant/writers),
  // header stamps 0, +1.1 ms and -0.7 ms apart, gyros from the unit simulator, accelerometers the
  // simulated specific force: the topics related by their time origins and paired.
  if (std::system("/usr/bin/python3 -c 'import rosbag' > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "python3-rosbag not installed (scripts/setup.sh installs it)";
  }
  TempDir dir;
  const Geometry g = make_geometry("triads:3");
  auto sensors = white_sensors(9);
  const std::int64_t offset_ns[3] = {0, 1'100'000, -700'000};
  for (std::size_t i = 0; i < 9; ++i) sensors[i].time_offset_s = static_cast<double>(offset_ns[i / 3]) * 1e-9;
  const double duration = 300.0;
  const auto motion = tumble_profile(150.0 * kDeg);
  const auto rec = simulate_unit(g, sensors, motion, kRate, duration, 2718);
  const auto force = specific_force(motion, kRate, duration);
  const std::size_t n = rec[0].size();
  std::string bin;
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t q = 0; q < n; ++q) {
      const std::int64_t stamp = 1'700'000'000'000'000'000LL + static_cast<std::int64_t>(q) * 5'000'000 + offset_ns[k];
      double v[6] = {rec[3 * k][q], rec[3 * k + 1][q], rec[3 * k + 2][q], force[0][q], force[1][q], force[2][q]};
      bin.append(reinterpret_cast<const char*>(&stamp), sizeof stamp);
      bin.append(reinterpret_cast<const char*>(v), sizeof v);
    }
  }
  const std::string in = dir.write("unit.bin", bin);
  const std::string bag = dir.file("unit.bag");
  const std::string writer = std::string(IMUNOISE_TEST_DATA_DIR) + "/../redundant/writers/write_imu_bag.py";
  ASSERT_EQ(std::system(("/usr/bin/python3 " + writer + " " + bag + " " + in + " /imu0,/imu1,/imu2 " +
                         std::to_string(n)).c_str()), 0);
  const auto r = run_cli({"redundant", "--geometry", "triads:3", "--in-motion", bag, "--topic", "/imu0,/imu1,/imu2",
                          "--per-sensor"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto im = nlohmann::json::parse(r.out).at("in_motion");
  ASSERT_EQ(im.at("sensors").size(), 9u);
  EXPECT_TRUE(im.at("leakage").at("g_sensitivity").get<bool>());  // the Imu messages carry the accelerometers
  std::size_t g_within = 0;
  for (std::size_t i = 0; i < 9; ++i) {
    const auto& s = im.at("sensors")[i];
    EXPECT_NE(s.at("source").get<std::string>().find(fmt::format("/imu{} gyro_{}", i / 3, "xyz"[i % 3])),
              std::string::npos) << s.at("source");
    const double ratio = s.at("fit").at("terms").at("N").at("value").get<double>() / sensors[i].noise.n_unit_sqrt_s;
    const auto& lk = s.at("leakage");
    std::printf("ROS bag sensor %zu: fitted N / true %.4f, time offset %.4f ms\n", i + 1, ratio,
                lk.at("time_offset_ms").get<double>());
    EXPECT_NEAR(ratio, 1.0, 0.05) << "sensor " << i + 1;
    // Offsets relative to the unit: instance k's minus the mean (0.1333 ms).
    EXPECT_NEAR(lk.at("time_offset_ms").get<double>(), static_cast<double>(offset_ns[i / 3]) * 1e-6 - 0.4 / 3, 0.02);
    for (std::size_t a = 0; a < 3; ++a) {
      const auto& g = lk.at("g_sensitivity");
      const double z = g.at("value")[a].get<double>() / g.at("se")[a].get<double>();
      g_within += std::abs(z) < 4 ? 1 : 0;
    }
  }
  EXPECT_EQ(g_within, 27u);  // no g-sensitivity simulated: none found beyond 4 standard errors
  EXPECT_NE(r.err.find("paired sample by sample"), std::string::npos) << r.err;
}

}  // namespace
