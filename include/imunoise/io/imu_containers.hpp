#pragma once
// Readers of IMU recordings in robotics containers. Each returns a Recording with the channels
// gyro_x gyro_y gyro_z (rad/s) and accel_x accel_y accel_z (m/s^2) for ROS sensor_msgs Imu
// messages, timed by header.stamp (integer ns), or the dataset's columns for HDF5.
//
// The bag, MCAP and ULog readers parse the documented formats themselves (ROS bag v2.0; MCAP
// v0; ULog v1; the ROS 2 SQLite bag is read with libsqlite3)
// with bounds checks on every field: a corrupt, truncated or hostile file is an InputError
// naming the file, the byte offset and the problem, never a crash (fuzzed: fuzz/). They read a
// memory-mapped file, or a buffer (`*_buffer`, used by the fuzzers and tests).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/io/recording.hpp"

namespace imunoise::io {

/// What a container holds, for the message listing the topics when the asked one is absent.
struct StreamInfo {
  std::string name;         ///< topic or dataset path
  std::string type;         ///< message type ("sensor_msgs/Imu") or "float64 [N x 6]"
  std::uint64_t count = 0;  ///< messages (or rows)
};

/// ROS 1 bag v2.0 (chunks uncompressed, bz2 or lz4). `topic`: a sensor_msgs/Imu topic.
Recording read_ros1_bag(const std::filesystem::path& path, std::string_view topic);
Recording read_ros1_bag_buffer(std::span<const unsigned char> bytes, std::string_view source,
                               std::string_view topic);

/// ROS 2 MCAP (chunks uncompressed, zstd or lz4; summary section used when present, a linear
/// scan otherwise). `topic`: a sensor_msgs/msg/Imu topic in CDR (or sensor_msgs/Imu in ros1
/// encoding).
Recording read_mcap(const std::filesystem::path& path, std::string_view topic);
Recording read_mcap_buffer(std::span<const unsigned char> bytes, std::string_view source,
                           std::string_view topic);

/// ROS 2 bag in SQLite3 storage: a .db3 file, or the bag directory (metadata.yaml and its .db3
/// files, read in the order metadata.yaml lists them). `topic`: a sensor_msgs/msg/Imu topic in
/// CDR. The database is opened read-only (never written, not even a lock or journal file).
Recording read_ros2_db3(const std::filesystem::path& path, std::string_view topic);

/// PX4 ULog (.ulg). `topic`: sensor_combined, vehicle_imu (delta angle / velocity divided by
/// their dt: rates), vehicle_angular_velocity, vehicle_acceleration, sensor_gyro or
/// sensor_accel. One instance gives gyro_x.. / accel_x..; several (multi_id 0, 1, ...) give
/// gyro0_x .. accel1_z, each instance with its own timestamps (Channel::time_s). Timestamps:
/// timestamp_sample when the topic has it, else timestamp (µs). Logger dropouts are counted in
/// Recording::notes.
Recording read_ulog(const std::filesystem::path& path, std::string_view topic);
Recording read_ulog_buffer(std::span<const unsigned char> bytes, std::string_view source,
                           std::string_view topic);

/// HDF5: a 1-D (N) or 2-D (N x C) numeric dataset; `time_dataset` (optional) a 1-D dataset of
/// N timestamps (integer ns, or seconds; a "units" attribute s/ms/us/ns overrides).
Recording read_hdf5(const std::filesystem::path& path, std::string_view dataset,
                    std::string_view time_dataset);

/// EuRoC / ASL `imu0/data.csv` (header "#timestamp [ns],w_RS_S_x [rad s^-1],...").
Recording read_euroc(const std::filesystem::path& path);

/// "  /imu/data  sensor_msgs/Imu  1200 messages\n" lines, for error messages.
std::string describe_streams(const std::vector<StreamInfo>& streams, std::string_view noun);

}  // namespace imunoise::io
