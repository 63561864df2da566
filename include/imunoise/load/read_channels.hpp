#pragma once
// Every channel of a file as the file states it (values unconverted, no integration), with the
// rate and the timing of its timestamps: for callers that want the samples themselves (Python's
// imunoise.read). The container, raw binary or text choice is load()'s.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/io/recording.hpp"
#include "imunoise/io/timestamps.hpp"

namespace imunoise::load {

struct ChannelsOptions {
  std::string file;
  std::string topic;                 ///< ROS bag / MCAP / ULog topic
  std::string dataset;               ///< HDF5 dataset
  std::string time_dataset;          ///< HDF5 dataset of timestamps
  std::vector<std::string> columns;  ///< keep only these channels (names, or 0-based indexes); empty: all
                                     ///< (channels sampled at different times, as a PX4 log's
                                     ///< IMU instances, are refused together)
  std::string time_column;           ///< text: column of timestamps
  std::string binary;                ///< raw binary layout f32|f64|i16|i32[:le|be] ("": by extension)
  std::size_t channels = 1;          ///< interleaved channels of raw binary input
  std::optional<double> rate_hz;     ///< for files without timestamps; checked against those with
};

struct FileRecording {
  io::Recording recording;
  double rate_hz = std::numeric_limits<double>::quiet_NaN();  ///< NaN: no timestamps, none given
  std::optional<io::TimingReport> timing;                     ///< when the file has timestamps
};

/// Reads the channels. The rate is 1 / the median interval of the timestamps; a given rate
/// more than 1 % away from it is an error, as are out-of-order timestamps. InputError naming
/// the file and the fix (options that do not apply to the file's kind, a non-numeric channel
/// of a raw binary file, a non-positive rate).
FileRecording read_channels(const ChannelsOptions& options);

}  // namespace imunoise::load
