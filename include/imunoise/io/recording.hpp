#pragma once
// A recording: named channels of samples sharing one set of timestamps, with their units and
// where they came from. Every reader of a multi-channel container (ROS 1 bag, ROS 2 MCAP,
// HDF5, EuRoC CSV) returns one, and the text reader's columns convert to one, so the commands
// (dev, fit, analyze, redundant --fuse) select a channel and check timing in one place.
//
// Values are as stored in the file (no unit conversion); `unit` says what they are in when the
// file says it (ROS messages: rad/s and m/s^2 by definition; EuRoC: from its header; HDF5: a
// "units" attribute), and is empty otherwise.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/units.hpp"

namespace imunoise::io {

/// One channel of a recording.
struct Channel {
  std::string name;              ///< e.g. "gyro_x", "accel_z", or a dataset/column name
  std::optional<Unit> unit;      ///< unit of `values` when the file states it
  std::vector<double> values;    ///< one per sample, in file order
  /// This channel's own sample times (seconds since Recording::time_origin) when they are not
  /// Recording::time_s: in a PX4 log each sensor instance is sampled on its own clock. Empty:
  /// the recording's time_s applies.
  std::vector<double> time_s = {};
};

/// The container a recording was read from.
enum class RecordingFormat { text, binary, euroc, hdf5, ros1_bag, mcap, ros2_db3, ulog };

/// "text", "binary", "EuRoC CSV", "HDF5", "ROS 1 bag", "MCAP", "ROS 2 bag (SQLite)", "PX4 ULog".
std::string_view format_name(RecordingFormat format);

struct Recording {
  std::string source;                  ///< file name used in messages
  RecordingFormat format = RecordingFormat::text;
  std::string stream;                  ///< topic or dataset read ("" for text/binary/EuRoC)
  std::string message_type;            ///< e.g. "sensor_msgs/Imu" (ROS containers only)
  /// Time of each sample in seconds since the first (time_s[0] == 0); empty when the file
  /// has no timestamps. From integer nanoseconds where the file stores them (exact to 1 ns).
  std::vector<double> time_s = {};
  std::string time_origin;             ///< first timestamp as stored (e.g. "1403636579758555392 ns")
  std::vector<Channel> channels;
  /// What the reader found that the user should know (PX4 logger dropouts), for Record::notes.
  std::vector<std::string> notes;

  [[nodiscard]] std::size_t sample_count() const {
    return channels.empty() ? 0 : channels.front().values.size();
  }
  /// The times of `c`: its own, or the recording's.
  [[nodiscard]] const std::vector<double>& times(const Channel& c) const { return c.time_s.empty() ? time_s : c.time_s; }
  /// Comma-separated channel names, for messages.
  [[nodiscard]] std::string channel_list() const;
  /// The channel named `name`, or with 0-based index `name` when it is all digits. Throws
  /// InputError naming the file and listing the channels.
  [[nodiscard]] const Channel& channel(std::string_view name) const;
};

/// What to read from a container: ROS topic, HDF5 dataset and optional time dataset.
struct RecordingOptions {
  std::string topic;         ///< ROS bag / MCAP: the sensor_msgs Imu topic; ULog: the uORB topic
  std::string dataset;       ///< HDF5: path of a 1-D (N) or 2-D (N x C) numeric dataset
  std::string time_dataset;  ///< HDF5: optional 1-D dataset of N timestamps
};

/// The container format of a file from its first bytes: the ROS bag, MCAP, SQLite (a ROS 2
/// bag), ULog and HDF5 magic numbers, or the EuRoC IMU header line ("#timestamp [ns],w_RS_S_x
/// [rad s^-1],..."); a directory holding a ROS 2 bag's metadata.yaml is a ROS 2 bag. nullopt
/// for anything else (text or raw binary, which the caller distinguishes by its options).
/// Throws InputError when the file cannot be opened.
std::optional<RecordingFormat> detect_container(const std::filesystem::path& path);

/// Reads a container file (bag, MCAP, ROS 2 SQLite bag, ULog, HDF5 or EuRoC, detected by
/// detect_container). Throws
/// InputError naming the file and the problem: unknown format, missing or wrong topic or
/// dataset (listing what the file holds), corrupt or truncated data.
Recording read_recording(const std::filesystem::path& path, const RecordingOptions& options);

/// A text file as a Recording: one channel per selected column (named by the header, else
/// "column K"), no unit (text files do not state one), and the time column when given (as
/// text_reader.hpp reads it). Reads through the text reader's public API, one pass per column.
/// Empty `columns`: every column except the time column. Throws InputError as the text reader.
/// The channels named (names or 0-based indices, in that order) of a recording; when they all
/// have their own time (Channel::time_s) and it is the same, it becomes the recording's time_s.
/// Throws InputError naming the channels when the chosen ones were sampled at different times
/// (separate sensors: read one at a time).
Recording select_channels(Recording recording, const std::vector<std::string>& names);

Recording read_text_recording(const std::filesystem::path& path, std::vector<std::string> columns,
                              const std::string& time_column = "");

}  // namespace imunoise::io
