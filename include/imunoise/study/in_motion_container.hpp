#pragma once
// A redundant unit whose sensors are all in one container: a PX4 log's sensor_gyro (and
// sensor_accel) multi-instances, vehicle_imu's instances, or the IMU topics of a ROS bag, MCAP or
// ROS 2 bag. The in-motion analysis (study/in_motion.hpp) takes one record per sensing axis; this
// reads them, instance-major (gyro0_x, gyro0_y, gyro0_z, gyro1_x, ...: the order of the built-in
// geometry triads:K), and brings the instances, each sampled on its own clock, to common times.
//
// Common times, without resampling the gyros. Interpolating a gyro between its samples would
// filter the very noise being measured: linear interpolation at a fraction f of the interval
// multiplies a white noise's variance at tau0 by (1 - f)^2 + f^2 (down to 1/2), differently for
// each sensor. So the gyro instances are paired sample by sample: instance i's sample q + s_i
// with the first instance's sample q, s_i chosen so that the first pair is the nearest, and the
// pairing is refused (naming the file, topic and instance) unless every pair's time offset stays
// within half a sample of the first pair's: no slip over the record. The instances must therefore
// run at one rate (1 / median interval within 0.1 %) without gaps. What is left is an offset of
// up to half a sample per instance (plus jitter), a timing leakage h_i . w' dt_i under motion;
// the analysis removes it by regression on the fused motion's derivative
// (InMotionOptions::remove_timing_leakage, set by analyze_container_unit's caller) and reports the
// offsets' mean and spread here (notes).
//
// Accelerometers (for the gyros' g-sensitivity): a regressor, not analysed, so they may be
// interpolated: every accelerometer instance is linearly interpolated onto the first gyro
// instance's times (refused where its samples are more than two of its intervals apart around a
// gyro time, or the gyro time is outside its span) and the specific force is the mean of the
// instances (co-aligned triads, body axes).
#include <array>
#include <span>
#include <string>
#include <vector>

#include "imunoise/load/load.hpp"
#include "imunoise/load/record.hpp"

namespace imunoise::study {

struct ContainerUnit {
  /// One record per sensing axis, instance-major, rates kept (SI), all of one length.
  std::vector<Record> gyros;
  /// The mean of the accelerometer instances on the gyros' times (m/s^2; x, y, z); empty
  /// when the container has no accelerometer on the topics read.
  std::array<std::vector<double>, 3> specific_force_m_s2;
  std::size_t accel_instances = 0;
  /// Per gyro instance: mean and spread (max - min) of its times minus the first instance's
  /// over the pairs (s); 0 for the first.
  std::vector<double> instance_offset_s;
  std::vector<double> instance_offset_spread_s;
  std::vector<std::string> notes;
};

/// True when `path` is a container (ROS bag, MCAP, ROS 2 bag, ULog, HDF5, EuRoC).
bool is_container_file(const std::string& path);

/// Reads the unit from `options.file`: the gyro instances of every topic in `topics` (in order;
/// one instance is a gyro_x/y/z triple of channels gyroK_x.. or gyro_x.., each instance on its own
/// timestamps) and the accelerometer instances (accelK_x.. / accel_x..) of the same topics and of
/// `accel_topics`. The unit of the values is the file's (rad/s, m/s^2) or options.units for the
/// gyros; the preprocessing of options (--skip, --detrend, ...) runs on each gyro record.
/// InputError naming the file, topic and instance: no gyro on a topic, an instance without its
/// three axes, instances at different rates, gaps or a pairing that slips, accelerometers that do
/// not cover the gyros' times.
ContainerUnit read_container_unit(const load::LoadOptions& options, std::span<const std::string> topics,
                                  std::span<const std::string> accel_topics);

/// The specific force (x, y, z) from accelerometer records taken as co-aligned triads in body
/// axes (x, y, z of triad 1, then of triad 2, ...): their mean per axis, SI. InputError naming
/// the files when their number is not a multiple of 3 or their lengths differ from `samples`.
std::array<std::vector<double>, 3> mean_specific_force(std::span<const Record> accels, std::size_t samples);

/// Pairs the samples of instances on their own clocks (header comment): for each instance the
/// first sample used and the common count; InputError naming `names[i]` on a slip.
struct InstancePairing {
  std::vector<std::size_t> first;   ///< per instance: index of its first paired sample
  std::size_t count = 0;            ///< pairs
  std::vector<double> mean_offset_s;
  std::vector<double> spread_s;
};
InstancePairing pair_instances(std::span<const std::span<const double>> times_s, std::span<const std::string> names);

}  // namespace imunoise::study
