// Round trip per filter: known coefficients -> the exported file -> read back as the consumer
// reads it -> discrete noise simulated the way the consumer uses the numbers (its own
// discretisation, from its source: docs/exports.md) -> Allan deviation with the library's
// estimator, which must lie inside the 68 % intervals of the original curve at every
// tau >= 2/rate. Files corrupted by the common mistakes (x sqrt(rate), / sqrt(rate), deg for
// rad, rad for deg, continuous for discrete, sigma for sigma^2) must fail the same check.
//
// Why this check is meaningful and the tolerance is not tuned: the original record and every
// consumer's record are built from the SAME standard-normal draws (common random numbers), so a
// file whose numbers the consumer turns into the original discrete noise reproduces the
// original curve up to rounding, and a file off by a factor r moves the curve by r. The 68 %
// interval of the original curve is the smallest error the record itself can resolve: a
// mistake inside it could not be seen in the user's data either. With 2^17 samples at 200 Hz
// (655 s) the interval is +-0.3 % at the shortest taus and about +-30 % at the longest, so
// every mistake above (factors 3.8 to 57) lands far outside at the short taus where white noise
// rules, while the correct files pass at every tau, the long ones where K rules included.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "consumer_readers.hpp"
#include "export_fixtures.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/export/gtsam.hpp"
#include "imunoise/export/kalibr.hpp"
#include "imunoise/export/matlab.hpp"
#include "imunoise/export/openvins.hpp"
#include "imunoise/export/orbslam3.hpp"
#include "imunoise/export/px4.hpp"
#include "imunoise/export/ros.hpp"
#include "imunoise/export/vins.hpp"
#include "imunoise/phase.hpp"

namespace imunoise::exports::test {
namespace {

constexpr std::size_t kSamples = std::size_t{1} << 17;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// Discrete noise as a consumer produces it: per-sample white std, per-sample bias step std,
/// at the consumer's own rate (PX4: its EKF rate).
struct Discrete {
  double white_sigma = 0.0;
  double walk_step_sigma = 0.0;
  double rate_hz = 0.0;
};

struct Draws {
  std::vector<double> white, walk;
};

Draws draws(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  Draws d;
  d.white.resize(kSamples);
  d.walk.resize(kSamples);
  for (auto& v : d.white) v = z(rng);
  for (auto& v : d.walk) v = z(rng);
  return d;
}

// Rate samples at d.rate_hz from the draws at kRateHz: a consumer at a lower rate (PX4's EKF
// integrates q IMU samples per step) sees the sum of q draws / sqrt(q), a standard normal.
std::vector<double> simulate(const Discrete& d, const Draws& z) {
  const auto q = static_cast<std::size_t>(std::lround(kRateHz / d.rate_hz));
  std::vector<double> rate;
  double bias = 0.0;
  for (std::size_t j = 0; (j + 1) * q <= kSamples; ++j) {
    double w = 0.0;
    double s = 0.0;
    for (std::size_t i = j * q; i < (j + 1) * q; ++i) {
      w += z.white[i];
      s += z.walk[i];
    }
    rate.push_back(d.white_sigma * w / std::sqrt(double(q)) + bias);
    bias += d.walk_step_sigma * s / std::sqrt(double(q));
  }
  return rate;
}

std::vector<DevPoint> curve(const std::vector<double>& rate, double rate_hz, bool intervals) {
  const auto phase = phase_from_rate(rate, 1.0 / rate_hz, 0.0);
  std::vector<std::size_t> m;
  for (std::size_t k = 1; k <= rate.size() / 5; k *= 2) m.push_back(k);
  auto points = oadev(phase, 1.0 / rate_hz, m);
  if (intervals) fill_confidence(points, Estimator::oadev, phase, 0.683);
  return points;
}

/// The taus (>= 2/rate of the consumer) where the consumer's curve leaves the original's 68 %
/// interval; empty = consistent.
std::vector<double> outside(const std::vector<DevPoint>& original, const std::vector<DevPoint>& consumer,
                            double consumer_rate_hz) {
  std::vector<double> bad;
  std::size_t compared = 0;
  for (const auto& p : consumer) {
    if (p.tau_s < 2.0 / consumer_rate_hz - 1e-12) continue;
    for (const auto& o : original) {
      if (std::abs(o.tau_s - p.tau_s) > 1e-9 * p.tau_s) continue;
      ++compared;
      if (!(p.dev >= o.ci_low && p.dev <= o.ci_high)) bad.push_back(p.tau_s);
    }
  }
  EXPECT_GE(compared, 10u) << "too few common taus to compare";
  return bad;
}

struct Consumer {
  const char* name;
  std::function<std::string(const ExportModel&)> render;
  std::function<FileValues(const std::string&)> read;
  /// The consumer's discretisation of (white, walk) as written in its file.
  std::function<Discrete(double white, double walk)> discretise;
  bool has_walk = true;
  bool variance = false;  ///< the file holds variances (sigma for sigma^2 is a mistake)
  bool discrete = false;  ///< the file holds discrete values (a density there is a mistake)
};

const double kSqrtF = std::sqrt(kRateHz);
constexpr double kPx4EkfHz = 100.0;

// Each consumer's discretisation, from its own source (docs/exports.md):
std::vector<Consumer> consumers() {
  const auto continuous = [](double w, double k) { return Discrete{w * kSqrtF, k / kSqrtF, kRateHz}; };
  return {
      // Kalibr's wiki: sigma_d = N sqrt(f), sigma_bd = K / sqrt(f).
      {"kalibr", kalibr_yaml, read_kalibr, continuous},
      // ov_msckf/src/state/Propagator.cpp: Qc = sigma_w^2 / dt, sigma_wb^2 dt.
      {"openvins", openvins_yaml, read_openvins, continuous},
      // src/Tracking.cc: Calib(Ng sqrt(freq), ..., Ngw / sqrt(freq)); covariance added per sample.
      {"orbslam3", orbslam3_yaml, read_orbslam3, continuous},
      // imuSensor: NoiseDensity sqrt(f) ("double-sided"), RandomWalk / sqrt(f).
      {"matlab", matlab_script, read_matlab, continuous},
      // CombinedImuFactor.cpp: wCov / dt per sample, dt biasOmegaCovariance per step.
      {"gtsam", [](const ExportModel& m) { return gtsam_json(m).dump(1); }, read_gtsam,
       [](double w, double k) { return Discrete{std::sqrt(w * kRateHz), std::sqrt(k / kRateHz), kRateHz}; }, true,
       true, false},
      // integration_base.h: gyr_n^2 on each sample, (gyr_w dt)^2 on the bias per step.
      {"vins", vins_yaml, read_vins, [](double w, double k) { return Discrete{w, k / kRateHz, kRateHz}; }, true,
       false, true},
      // covariance.cpp: (dt_e EKF2_GYR_NOISE)^2 per EKF step = rate std EKF2_GYR_NOISE at f_e,
      // (dt_e EKF2_GYR_B_NOISE)^2 bias growth per step.
      {"px4", px4_params, read_px4, [](double w, double k) { return Discrete{w, k / kPx4EkfHz, kPx4EkfHz}; }, true,
       false, true},
      // sensor_msgs/Imu: the covariance of one sample.
      {"ros", ros_covariance_yaml, read_ros, [](double w, double) { return Discrete{std::sqrt(w), 0.0, kRateHz}; },
       false, true, true},
  };
}

struct Corruption {
  const char* name;
  std::function<double(double)> apply;
};

// Each mistake applied to the value as written in the file.
std::vector<Corruption> corruptions(const Consumer& c) {
  // Between a density and a discrete value at the consumer's rate: sqrt(f) on a sigma, f on a
  // variance (PX4's rate is its EKF's).
  const double f = std::string(c.name) == "px4" ? kPx4EkfHz : kRateHz;
  const double conv = c.variance ? f : std::sqrt(f);
  const double deg = c.variance ? kDegPerRad * kDegPerRad : kDegPerRad;
  std::vector<Corruption> out{
      {"x sqrt(rate)", [](double v) { return v * kSqrtF; }},
      {"/ sqrt(rate)", [](double v) { return v / kSqrtF; }},
      {"deg for rad", [=](double v) { return v * deg; }},
      {"rad for deg", [=](double v) { return v / deg; }},
  };
  if (c.discrete) {
    out.push_back({"continuous for discrete", [=](double v) { return v / conv; }});
  } else {
    out.push_back({"discrete for continuous", [=](double v) { return v * conv; }});
  }
  if (c.variance) out.push_back({"sigma for sigma^2", [](double v) { return std::sqrt(v); }});
  return out;
}

struct Sensor {
  const char* name;
  double n, k;
  unsigned seed;
};

class RoundTrip : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (int s = 0; s < 2; ++s) {
      const Sensor& sensor = kSensors[s];
      z_[s] = draws(sensor.seed);
      for (int walk = 0; walk < 2; ++walk) {
        const Discrete truth{sensor.n * kSqrtF, walk ? sensor.k / kSqrtF : 0.0, kRateHz};
        original_[s][walk] = curve(simulate(truth, z_[s]), kRateHz, true);
      }
    }
  }
  static constexpr Sensor kSensors[2] = {{"gyro", kGyroN, kGyroK, 11}, {"accel", kAccelN, kAccelK, 23}};
  static Draws z_[2];
  static std::vector<DevPoint> original_[2][2];  // [sensor][with walk]

  // Taus outside the interval for a consumer's file values of one sensor.
  static std::vector<double> check(const Consumer& c, int s, double white, std::optional<double> walk) {
    const Discrete d = c.discretise(white, walk.value_or(0.0));
    return outside(original_[s][c.has_walk ? 1 : 0], curve(simulate(d, z_[s]), d.rate_hz, false), d.rate_hz);
  }
};
Draws RoundTrip::z_[2];
std::vector<DevPoint> RoundTrip::original_[2][2];

TEST_F(RoundTrip, EveryTargetReproducesTheOriginalCurve) {
  for (const auto& c : consumers()) {
    const FileValues v = c.read(c.render(model()));
    ASSERT_TRUE(v.gyro_white && v.accel_white) << c.name;
    if (c.has_walk) ASSERT_TRUE(v.gyro_walk && v.accel_walk) << c.name;
    const auto gyro = check(c, 0, *v.gyro_white, v.gyro_walk);
    const auto accel = check(c, 1, *v.accel_white, v.accel_walk);
    EXPECT_TRUE(gyro.empty()) << c.name << " gyro leaves the 68 % interval at " << gyro.size() << " taus, first "
                              << (gyro.empty() ? 0.0 : gyro.front()) << " s";
    EXPECT_TRUE(accel.empty()) << c.name << " accel leaves the 68 % interval at " << accel.size()
                               << " taus, first " << (accel.empty() ? 0.0 : accel.front()) << " s";
  }
}

TEST_F(RoundTrip, EveryCorruptedFileFails) {
  for (const auto& c : consumers()) {
    const FileValues v = c.read(c.render(model()));
    for (const auto& bad : corruptions(c)) {
      const auto walk = [&](std::optional<double> w) { return w ? std::optional(bad.apply(*w)) : w; };
      EXPECT_FALSE(check(c, 0, bad.apply(*v.gyro_white), walk(v.gyro_walk)).empty())
          << c.name << " gyro file corrupted by " << bad.name << " passed the check";
      EXPECT_FALSE(check(c, 1, bad.apply(*v.accel_white), walk(v.accel_walk)).empty())
          << c.name << " accel file corrupted by " << bad.name << " passed the check";
    }
  }
}

// The check resolves the walk too: a file whose K alone is off by sqrt(rate) fails at the long
// taus, where the white noise no longer hides it.
TEST_F(RoundTrip, AWrongWalkAloneFails) {
  for (const auto& c : consumers()) {
    if (!c.has_walk) continue;
    const FileValues v = c.read(c.render(model()));
    const double factor = c.variance ? kRateHz : kSqrtF;
    EXPECT_FALSE(check(c, 0, *v.gyro_white, *v.gyro_walk * factor).empty()) << c.name;
    EXPECT_FALSE(check(c, 0, *v.gyro_white, *v.gyro_walk / factor).empty()) << c.name;
  }
}

}  // namespace
}  // namespace imunoise::exports::test
