// The parameter audit: the table of what each key means agrees with the renderers, a file
// imunoise wrote is consistent with its own model, and files carrying the known mistakes are
// named by their mistake (or as inflated / too small), with ok = false for an error.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "export_fixtures.hpp"
#include "imunoise/error.hpp"
#include "imunoise/export/audit.hpp"
#include "imunoise/export/export_target.hpp"
#include "imunoise/export/read_params.hpp"
#include "imunoise/export/target_keys.hpp"

namespace imunoise::exports::test {
namespace {

ParamsFile rendered(Target t, const ExportModel& m) {
  const auto files = render_target({t, ""}, m, "");
  return read_params_text(files.front().text, files.front().path, std::nullopt);
}

TEST(ExportAudit, TableAgreesWithEveryRenderer) {
  const auto m = model();
  for (auto t : all_targets()) {
    const auto f = rendered(t, m);
    EXPECT_EQ(f.target, t == Target::kalibr ? Target::kalibr : t) << target_name(t);
    EXPECT_TRUE(f.target_detected);
    EXPECT_EQ(f.values.size(), target_keys(t).size()) << target_name(t);
    for (const auto& v : f.values) {
      const auto& s = v.spec.sensor == Sensor::gyro ? m.gyro : m.accel;
      const double c = v.spec.term == Term::white ? s->coefficients.random_walk.value
                                                  : s->coefficients.rate_random_walk.value;
      EXPECT_NEAR(v.value, file_value(v.spec.form, c, kRateHz, 100.0), 1e-14 * v.value) << v.spec.key;
    }
    const auto r = audit(f, m);
    EXPECT_TRUE(r.ok) << target_name(t);
    for (const auto& i : r.items) EXPECT_EQ(i.verdict, Verdict::consistent) << target_name(t) << " " << i.message;
  }
}

// A model whose every N and K is scaled by `k` (the renderer then writes the slip's values).
ExportModel scaled(double k, std::function<double(double)> g = nullptr) {
  auto m = model();
  for (auto* s : {&*m.gyro, &*m.accel}) {
    for (auto* c : {&s->coefficients.random_walk, &s->coefficients.rate_random_walk}) {
      c->value = g ? g(c->value) : c->value * k;
    }
  }
  return m;
}

void expect_all(const AuditResult& r, Verdict v, const std::string& label, bool ok) {
  EXPECT_EQ(r.ok, ok);
  ASSERT_FALSE(r.items.empty());
  for (const auto& i : r.items) {
    EXPECT_EQ(i.verdict, v) << i.param.spec.key << ": " << i.message;
    if (!label.empty()) EXPECT_NE(i.mistake.find(label), std::string::npos) << i.param.spec.key << ": " << i.mistake;
  }
}

TEST(ExportAudit, KnownMistakesAreNamed) {
  const double s = std::sqrt(kRateHz);
  const double deg = 180.0 / std::numbers::pi;
  const auto truth = model();
  // Kalibr given discrete per-sample values (N sqrt(f)).
  expect_all(audit(rendered(Target::kalibr, scaled(s)), truth), Verdict::mistake, "x sqrt(rate)", false);
  // VINS given Kalibr's densities.
  expect_all(audit(rendered(Target::vins, scaled(1.0 / s)), truth), Verdict::mistake, "/ sqrt(rate)", false);
  // ORB-SLAM3 in degrees.
  expect_all(audit(rendered(Target::orbslam3, scaled(deg)), truth), Verdict::mistake, "deg for rad", false);
  // GTSAM given sigma where sigma^2 belongs: the renderer squares sqrt(c).
  expect_all(audit(rendered(Target::gtsam, scaled(0, [](double c) { return std::sqrt(c); })), truth),
             Verdict::mistake, "sigma for sigma^2", false);
  // ROS given the PSD N^2 instead of the per-sample variance N^2 f.
  expect_all(audit(rendered(Target::ros, scaled(1.0 / s)), truth), Verdict::mistake, "/ rate", false);
  // PX4 discretised at the IMU rate (200 Hz) instead of the EKF's 100 Hz.
  auto at_imu_rate = model();
  at_imu_rate.px4_ekf_rate_hz = kRateHz;
  expect_all(audit(rendered(Target::px4, at_imu_rate), truth), Verdict::mistake, "sqrt(IMU rate / EKF rate)", false);
  // A deliberate margin is reported, not an error; a smaller value is.
  expect_all(audit(rendered(Target::matlab, scaled(2.0)), truth), Verdict::inflated, "", true);
  const auto halved = audit(rendered(Target::openvins, scaled(0.5)), truth);
  expect_all(halved, Verdict::too_small, "", false);
  EXPECT_NE(halved.items[0].message.find("over-confident"), std::string::npos);
  EXPECT_NEAR(audit(rendered(Target::matlab, scaled(2.0)), truth).items[0].ratio, 2.0, 1e-12);
}

TEST(ExportAudit, TermsTheRecordingLacksAreNotChecked) {
  auto gyro_only = model(false);
  gyro_only.gyro->coefficients.rate_random_walk = Coefficient{};
  const auto r = audit(rendered(Target::kalibr, model()), gyro_only);
  EXPECT_TRUE(r.ok);
  int not_checked = 0;
  for (const auto& i : r.items) not_checked += i.verdict == Verdict::not_checked;
  EXPECT_EQ(not_checked, 3);
  const auto j = audit_json(r);
  EXPECT_EQ(j["values"][1]["verdict"], "not_checked");
  EXPECT_FALSE(j["values"][1].contains("expected"));
  EXPECT_EQ(j["target"], "kalibr");
}

TEST(ExportAudit, ReaderRefusesWhatItCannotRead) {
  EXPECT_THROW(read_params_text("a: 1\n", "x.yaml"), InputError);
  try {
    read_params_text("a: 1\n", "x.yaml");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("give --target T; targets: kalibr openvins"), std::string::npos);
  }
  EXPECT_THROW(read_params_text("gyr_n: abc\n", "v.yaml"), InputError);
  EXPECT_THROW(read_params_text("1\t1\tEKF2_GYR_NOISE\n", "p.params"), InputError);
  EXPECT_THROW(read_params_text("a: 1\n", "x.yaml", Target::vins), InputError);  // none of its keys
  EXPECT_THROW(read_params_text("angular_velocity_covariance: [1, 0, 0, 0, 2, 0, 0, 0, 1]\n", "r.yaml"), InputError);
  EXPECT_THROW(read_params_text("hello\n", "x.yaml", Target::openvins), InputError);  // a scalar, not a map
  EXPECT_THROW(read_params_text("gyr_n: -1\n", "v.yaml"), InputError);
  EXPECT_THROW(read_params_text("1\t1\tEKF2_GYR_NOISE\tnan\t9\n", "p.params"), InputError);
  // ROS's own "not provided" (-1 in element 0) is a missing value, not an error.
  const auto ros = read_params_text(
      "angular_velocity_covariance: [-1, 0, 0, 0, 0, 0, 0, 0, 0]\n"
      "linear_acceleration_covariance: [0.1, 0, 0, 0, 0.1, 0, 0, 0, 0.1]\n", "r.yaml");
  EXPECT_EQ(ros.values.size(), 1u);
  EXPECT_EQ(ros.missing, std::vector<std::string>{"angular_velocity_covariance"});
  // OpenCV's header line and a commented key (a placeholder) are understood.
  const auto f = read_params_text("%YAML:1.0\n# acc_n: <FILL IN>\ngyr_n: 0.01\n", "v.yaml");
  EXPECT_EQ(f.target, Target::vins);
  EXPECT_EQ(f.values.size(), 1u);
  EXPECT_EQ(f.missing.size(), 3u);
}

}  // namespace
}  // namespace imunoise::exports::test
