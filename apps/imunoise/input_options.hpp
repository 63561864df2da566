#pragma once
// The input options shared by every command that reads a sensor record (dev, fit, analyze),
// and the one function that turns them into angle (phase) samples in SI units.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "imunoise/fit/fit.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/io/recording.hpp"
#include "imunoise/io/timestamps.hpp"
#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/preprocess/temperature.hpp"
#include "imunoise/series.hpp"
#include "imunoise/units.hpp"

namespace imunoise::cli {

struct InputOptions {
  std::string file;              ///< path, or "-" for standard input
  std::string column;            ///< --column N|NAME (0-based index or header name)
  std::string time_column;       ///< --time-column N|NAME
  std::string binary;            ///< --binary f32|f64|i16|i32[:le|be]
  std::size_t channels = 1;      ///< --channels (binary)
  double rate_hz = 0.0;          ///< --rate (0: derive from the time column)
  std::string input = "rate";    ///< --input rate|angle (freq|phase)
  std::string units;             ///< --units of the values in the file (after scaling)
  double scale = 1.0;            ///< --scale: value = raw * scale
  double sensitivity = 0.0;      ///< --sensitivity: value = raw / sensitivity (0: unset)
  bool allow_gaps = false;       ///< --allow-gaps
  std::string topic;             ///< --topic (ROS 1 bag, MCAP)
  std::string dataset;           ///< --dataset (HDF5)
  std::string time_dataset;      ///< --time-dataset (HDF5)
  // Preprocessing (rate input): every step is reported in PhaseRecord::preprocessing.
  std::string skip;              ///< --skip DURATION (s, min, h suffix) or "auto" (from DAVAR)
  std::string detrend = "none";  ///< --detrend none|linear|quadratic
  std::string outliers;          ///< --outliers fail|report|reject ("" = not checked)
  std::string gaps;              ///< --gaps fail|split ("" = fail, unless --allow-gaps)
  bool davar = false;            ///< --davar: dynamic Allan variance and stationarity verdict
  double davar_window_s = 0.0;   ///< --davar-window (0: record / 20)
  std::string temperature;       ///< --temperature COLUMN|CHANNEL: bin the analysis by temperature
  double temperature_bin = 5.0;  ///< --temperature-bin WIDTH (the temperature channel's unit)
  /// Options of the per-bin noise-model fits (set by `fit` to its own; default otherwise).
  std::optional<fit::FitOptions> temperature_fit;
};

void add_input_options(CLI::App& command, InputOptions& options);

/// A record ready for the estimators.
struct PhaseRecord {
  std::string source;            ///< file name as given ("-" is "standard input")
  InputKind kind = InputKind::rate;
  double rate_hz = 0.0;
  std::size_t n_samples = 0;     ///< samples in the file (rate samples, or angle samples)
  std::vector<double> phase_si;  ///< angle samples in SI (rad, m/s, s or unit*s)
  Unit rate_unit;                ///< unit deviations are reported in
  bool unit_given = false;       ///< false when --units was not given (label "input unit")
  std::optional<io::TimingReport> timing;
  std::string format;            ///< container read ("text", "binary", "ROS 1 bag", "MCAP", ...)
  std::string stream;            ///< topic or dataset read, when the container has several
  std::string channel;           ///< channel read (e.g. "gyro_x"), when the container names them
  /// One line per preprocessing step: what was removed and how much.
  std::vector<std::string> preprocessing;
  /// More than one when the record was split (--gaps split, --outliers reject): rate-sample
  /// ranges analysed as independent segments whose Allan sums are pooled (never joined).
  std::vector<preprocess::Segment> segments;
  std::vector<double> rate_si;   ///< the rate samples (SI), kept only when split into segments
  std::optional<preprocess::DavarResult> davar;
  std::vector<preprocess::TemperatureBin> temperature_bins;  ///< with --temperature
};

/// Reads, checks and integrates the input. Raw binary files are streamed in chunks straight
/// into the phase array, so peak memory is one double per sample plus a 1 MB buffer.
/// Throws InputError with the file, line or sample and the fix.
PhaseRecord load_phase(const InputOptions& options);

/// What load_phase would read, without reading the samples: the record's description (source,
/// kind, rate, units; phase_si empty, n_samples 0) and, for a raw binary file, its read options
/// and the factor to SI. For the sliced reads of `--mpi` (each rank reads its own records).
struct RecordPlan {
  PhaseRecord meta;
  bool binary = false;
  io::BinaryReadOptions read;   ///< binary only
  double to_si = 1.0;           ///< value in SI = raw value * to_si
};
RecordPlan plan_record(const InputOptions& options);

/// Label for a unit in output: its name, or "input unit" (with suffix) when none was given.
std::string unit_label(const PhaseRecord& record, bool integrated = false);

}  // namespace imunoise::cli
