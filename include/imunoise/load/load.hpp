#pragma once
// The one place where a file becomes a Record: container, raw binary or text; the channel; the
// units to SI; the rate (given, or from the timestamps, checked for gaps and mixed rates);
// the preprocessing steps; the rate offset and the integration to phase (load/integrate.hpp).
// Every command and every Python entry point loads through here.
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "imunoise/fit/fit.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/load/record.hpp"
#include "imunoise/preprocess/pipeline.hpp"

namespace imunoise::load {

struct LoadOptions {
  std::string file;              ///< path, or "-" for standard input
  std::string column;            ///< channel: 0-based index or header / channel name
  std::string time_column;       ///< text: column of timestamps (s, or integer ns)
  std::string binary;            ///< raw binary layout f32|f64|i16|i32[:le|be] ("": by extension)
  std::size_t channels = 1;      ///< interleaved channels of raw binary input
  double rate_hz = 0.0;          ///< 0: from the timestamps (or a simulated file's header)
  std::string input = "rate";    ///< rate|angle (freq|phase)
  std::string units;             ///< unit of the values after scaling ("": "input unit")
  double scale = 1.0;            ///< value = raw * scale
  double sensitivity = 0.0;      ///< value = raw / sensitivity (0: unset)
  bool allow_gaps = false;       ///< treat a record with timestamp gaps as equally spaced
  std::string topic;             ///< ROS 1 bag / MCAP topic
  std::string dataset;           ///< HDF5 dataset
  std::string time_dataset;      ///< HDF5 dataset of timestamps
  // Preprocessing of rate samples, each step reported in Record::preprocessing.
  std::string skip;              ///< duration (s, min, h suffix) or "auto" (from DAVAR)
  std::string detrend = "none";  ///< none|linear|quadratic
  std::string outliers;          ///< fail|report|reject ("": not checked)
  std::string gaps;              ///< fail|split ("": fail, unless allow_gaps)
  bool davar = false;            ///< dynamic Allan variance and stationarity verdict
  double davar_window_s = 0.0;   ///< 0: record / 20
  std::string temperature;       ///< temperature column / channel: analysis per temperature bin
  double temperature_bin = 5.0;  ///< bin width, in the temperature channel's unit
  /// Options of the per-bin noise-model fits (the defaults when not given).
  std::optional<fit::FitOptions> temperature_fit;
  /// Keep the (preprocessed) rate samples in SI in Record::rate_si beside the phase, for
  /// callers that need the rates themselves (the fusion of a redundant unit).
  bool keep_rates = false;
};

/// Reads, checks, preprocesses and integrates one channel. A text file without --rate or a
/// time column whose header names a timestamp column (t, time, timestamp, ...) is read with
/// that column as its time column, said in Record::notes. Raw binary files without
/// preprocessing are streamed in chunks straight into the phase array, so peak memory is one
/// double per sample plus a 1 MB buffer. Record::name is the source. Throws InputError naming
/// the file, line, column or sample, and the fix.
Record load(const LoadOptions& options);

/// The preprocessing options the loader runs (preprocess/pipeline.hpp).
preprocess::PipelineOptions pipeline_options(const LoadOptions& options);

/// The rest of the road for rate samples already in SI (from a file or an array): the
/// preprocessing steps, the split into segments, the integration to phase, the overflow
/// check. `record` carries the description (source, rate, unit); `gap_breaks` are the first
/// samples after each timestamp gap (used with split_gaps), `temperature` one value per sample
/// or empty. With keep_rates the rates stay in Record::rate_si.
Record finish_rates(Record record, std::vector<double> rate_si, const preprocess::PipelineOptions& options,
                    std::span<const std::size_t> gap_breaks = {}, std::vector<double> temperature = {},
                    bool keep_rates = false);

/// What load() would read, without reading the samples: the record's description (phase_si
/// empty, n_samples 0) and, for a raw binary file, its read options and the factor to SI. For
/// the sliced reads of `--mpi` (each rank reads its own records).
struct RecordPlan {
  Record meta;
  bool binary = false;
  io::BinaryReadOptions read;   ///< binary only
  double to_si = 1.0;           ///< value in SI = raw value * to_si
};
RecordPlan plan_record(const LoadOptions& options);

/// Records in a planned raw binary file and, with `with_offset`, the rate offset its first
/// samples give (the serial loader's offset; 0 for angle input): what a sliced read learns
/// first (rank 0 the offset, every rank the count).
struct BinaryLayout {
  std::size_t records = 0;
  double rate_offset_si = 0.0;
};
BinaryLayout binary_layout(const RecordPlan& plan, const std::string& path, bool with_offset);

/// The phase (SI) of the records [first, first + count) of a planned raw binary file: rate
/// records integrated from `rate_offset_si` (count + 1 phase samples, the first 0), angle
/// records as they are. Slices integrated from one offset join exactly into the serial
/// record. InputError naming the file on a short read or an overflowing integral.
std::vector<double> read_phase_slice(const RecordPlan& plan, const std::string& path, std::size_t first,
                                     std::size_t count, double rate_offset_si);

/// The value channels a file holds, in order, for a study of all of them: a container's
/// channel names, a raw binary file's channel indexes, a text file's header names (or column
/// indexes without a header) but the time column. A text column named like a timestamp (t,
/// time, timestamp, ...) is never a value channel: when no time column was given it is
/// returned in `time_column` (to be used as one) with a note saying so.
struct FileChannels {
  std::vector<std::string> names;
  bool named = false;            ///< names come from a header or the container
  bool binary = false;
  std::string time_column;       ///< a timestamp-like column found when none was given
  std::string note;              ///< what was decided about it
};
FileChannels file_channels(const LoadOptions& options);

/// One channel of a study of many files: how to load it, its name in the report (its column
/// or channel name, prefixed with the file's stem when several files are studied; the stem for
/// a file of one unnamed channel), and what was decided about its file (a column read as time).
struct ChannelPlan {
  LoadOptions options;
  std::string name;
  std::string note;
};

/// Every (file, channel) pair of a study: the `columns_list` (comma list; empty: every value
/// channel of each file, file_channels), names from `names_list` (comma list, one per channel)
/// or derived, the unit from `shared.units` (one for all, or a comma list, one per channel).
/// A file whose channels cannot be listed is an InputError, or with `keep_going` reported to
/// `failed(file, error)` and skipped. InputError when the names or units do not count the
/// channels.
std::vector<ChannelPlan> plan_channels(std::span<const std::string> files, const std::string& columns_list,
                                       const std::string& names_list, const LoadOptions& shared, bool keep_going,
                                       const std::function<void(const std::string& file, const std::string& error)>& failed);

/// Loads every planned channel, named as planned. A channel that cannot be loaded is an
/// InputError (saying --keep-going would skip it when there are several), or with `keep_going`
/// reported to `skipped(file, error)` and left out. `before(i)` runs before channel i (progress).
std::vector<Record> load_channels(std::span<const ChannelPlan> plan, bool keep_going,
                                  const std::function<void(const std::string& file, const std::string& error)>& skipped,
                                  const std::function<void(std::size_t)>& before = {});

}  // namespace imunoise::load
