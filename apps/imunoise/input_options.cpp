#include "input_options.hpp"

#include <fmt/core.h>

namespace imunoise::cli {
namespace {

// Every input option but the positional file(s), the column choice and --units.
void add_shared_input_options(CLI::App& command, load::LoadOptions& options) {
  command.add_option("--rate", options.rate_hz, "sample rate (Hz)");
  command.add_option("--input", options.input, "what the samples are: rate (freq) or angle (phase)")
      ->capture_default_str();
  command.add_option("--time-column", options.time_column,
                     "column of timestamps (s, or integer ns); derives the rate and checks gaps");
  command.add_flag("--allow-gaps", options.allow_gaps,
                   "treat a record with timestamp gaps as equally spaced (never interpolated)");
  command.add_option("--topic", options.topic,
                     "ROS 1 bag / MCAP: topic of sensor_msgs Imu messages (channels gyro_x gyro_y "
                     "gyro_z accel_x accel_y accel_z; choose with --column)");
  command.add_option("--dataset", options.dataset, "HDF5: dataset path, 1-D or 2-D (N x channels)");
  command.add_option("--time-dataset", options.time_dataset,
                     "HDF5: 1-D dataset of timestamps (integer ns, or s; a units attribute overrides)");
  command.add_option("--skip", options.skip,
                     "remove a warm-up: DURATION (30, 30s, 5min, 0.5h) or auto (from the dynamic Allan variance)");
  command.add_option("--detrend", options.detrend,
                     "subtract a polynomial in time: none, linear, quadratic (removes rate ramp R and "
                     "biases rate random walk K low)")
      ->capture_default_str();
  command.add_option("--outliers", options.outliers,
                     "spikes by robust MAD: fail, report, or reject (removed; the record split at each)");
  command.add_option("--gaps", options.gaps,
                     "timestamp gaps: fail (default), or split (segments whose sums are pooled for "
                     "adev oadev mdev tdev hdev ohdev and the fit; never interpolated)");
  command.add_flag("--davar", options.davar,
                   "dynamic Allan variance (sliding window) and a stationarity verdict");
  command.add_option("--davar-window", options.davar_window_s, "DAVAR window (s); default record / 20");
  command.add_option("--temperature", options.temperature,
                     "temperature column/channel: bias and the noise-model fit (Q N B K with "
                     "intervals) per temperature bin");
  command.add_option("--temperature-bin", options.temperature_bin, "temperature bin width (channel's unit)")
      ->capture_default_str();
  command.add_option("--binary", options.binary, "raw binary samples: f32|f64|i16|i32[:le|be]");
  command.add_option("--channels", options.channels, "interleaved channels in binary input")
      ->check(CLI::Range(std::size_t{1}, std::size_t{65536}));
  command.add_option("--scale", options.scale, "multiply raw values by this factor (e.g. units per ADC count)");
  command.add_option("--sensitivity", options.sensitivity,
                     "divide raw values by this sensitivity (e.g. 0.02 for 20 mV per deg/s)");
}

}  // namespace

void add_input_options(CLI::App& command, load::LoadOptions& options) {
  command.add_option("file", options.file, "input file (text, raw binary, ROS 1 bag, MCAP, HDF5 or EuRoC CSV); - for standard input")
      ->required();
  add_load_options(command, options);
}

void add_load_options(CLI::App& command, load::LoadOptions& options) {
  command.add_option("--units", options.units,
                     "unit of the values (after --scale), e.g. deg/s, rad/s, deg/h, m/s^2, g; "
                     "angle input: deg, rad");
  command.add_option("--column", options.column, "column to read: 0-based index or header name; "
                                                  "binary: channel index; containers: channel name");
  add_shared_input_options(command, options);
}

void add_multi_input_options(CLI::App& command, MultiInputOptions& options, const std::string& files_help) {
  command.add_option("files", options.files, files_help)->required();
  command.add_option("--units", options.load.units,
                     "unit of the values (after --scale: deg/s, rad/s, m/s^2, g, ...): one for every "
                     "channel or a comma list, one per channel");
  command.add_option("--columns,--column", options.columns,
                     "value columns (header names, 0-based indexes or container channel names, comma "
                     "list); default: every column but the time column");
  add_shared_input_options(command, options.load);
}

void print_load_notes(const Record& record) {
  for (const auto& note : record.notes) fmt::print(stderr, "imunoise: {}\n", note);
}

}  // namespace imunoise::cli
