#include "input_options.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/io/recording.hpp"
#include "imunoise/io/text_reader.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/preprocess/pipeline.hpp"

namespace imunoise::cli {
namespace {

// The rate offset removed before integration: the mean of the first samples. Every estimator
// cancels a constant rate exactly, so this only keeps the phase small (no cancellation); using
// a prefix lets binary files be integrated in one streaming pass.
constexpr std::size_t kOffsetSamples = std::size_t{1} << 20;

std::string source_name(const std::string& file) {
  return file == "-" ? "standard input" : file;
}

// A neutral unit for records whose unit was not given: no conversion, labelled at the edges.
Unit unit_of(const InputOptions& options, InputKind kind, bool& given) {
  given = !options.units.empty();
  if (!given) return Unit{"input unit", kind == InputKind::rate ? Quantity::dimensionless : Quantity::time, 1.0};
  Unit unit = parse_unit(options.units);
  if (kind == InputKind::rate) {
    if (unit.quantity == Quantity::angle || unit.quantity == Quantity::time) {
      throw InputError("--units " + options.units + " is an angle or time unit but --input is rate; " +
                       "pass --input angle, or a rate unit such as deg/s");
    }
    return unit;
  }
  if (unit.quantity != Quantity::angle && unit.quantity != Quantity::velocity &&
      unit.quantity != Quantity::time) {
    throw InputError("--units " + options.units + " is not an angle unit but --input is angle; " +
                     "pass --input rate, or an angle unit such as deg or rad");
  }
  return unit;
}

double value_scale(const InputOptions& options) {
  if (!std::isfinite(options.scale) || options.scale == 0.0) {
    throw InputError("--scale must be finite and non-zero, got " + fmt::format("{}", options.scale));
  }
  if (options.sensitivity != 0.0) {
    if (!std::isfinite(options.sensitivity)) throw InputError("--sensitivity must be finite");
    return options.scale / options.sensitivity;
  }
  return options.scale;
}

// Reserves room for the whole phase array and asks for transparent huge pages on it: a
// 1e8-sample record is 800 MB, and with 4 KB pages its first touch costs 200 000 page faults.
void reserve_phase(std::vector<double>& phase, std::size_t count) {
  phase.reserve(count);
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  const auto begin = (reinterpret_cast<std::uintptr_t>(phase.data()) + huge - 1) & ~(huge - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(phase.data() + count)) & ~(huge - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

bool is_binary(const InputOptions& options) {
  return !options.binary.empty() ||
         (options.file != "-" && io::binary_format_from_extension(options.file).has_value());
}

io::BinaryReadOptions binary_options(const InputOptions& options) {
  io::BinaryReadOptions read;
  if (!options.binary.empty()) {
    read.format = io::parse_binary_format(options.binary);
  } else {
    read.format = *io::binary_format_from_extension(options.file);
  }
  read.channels = options.channels;
  if (!options.column.empty()) {
    const auto selector = io::parse_column_selector(options.column);
    if (!std::holds_alternative<std::size_t>(selector)) {
      throw InputError("--column must be a channel index (0-based) for binary input, got '" +
                       options.column + "'");
    }
    read.column = std::get<std::size_t>(selector);
  }
  return read;
}

// Sample rates outside this range are a typo or a unit mix-up (Hz vs kHz vs period), not a sensor.
constexpr double kMinRateHz = 1e-6;
constexpr double kMaxRateHz = 1e9;

void require_rate(double rate_hz, const std::string& source) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError(source + ": the sample rate must be positive and finite, got " +
                     fmt::format("{}", rate_hz) + " Hz; pass --rate HZ or --time-column");
  }
  if (rate_hz < kMinRateHz || rate_hz > kMaxRateHz) {
    throw InputError(source + ": a sample rate of " + fmt::format("{}", rate_hz) +
                     " Hz is outside " + fmt::format("{:g}..{:g}", kMinRateHz, kMaxRateHz) +
                     " Hz; --rate is in Hz (samples per second)");
  }
}

// Values so large that their running integral overflows cannot be analysed; say so instead of
// printing NaN.
void require_finite_phase(const PhaseRecord& record) {
  if (const std::size_t k = first_non_finite(record.phase_si, 0); k < record.phase_si.size()) {
    throw InputError(record.source + ": the integral of the samples overflows at sample " +
                     std::to_string(k) + "; check --units, --scale and --sensitivity");
  }
}

// Rate or angle samples (already in SI) into the record's phase array.
void integrate_into(PhaseRecord& record, std::span<const double> values_si) {
  if (record.kind == InputKind::angle) {
    record.phase_si.assign(values_si.begin(), values_si.end());
    return;
  }
  const double offset = compensated_mean(values_si.first(std::min(values_si.size(), kOffsetSamples)));
  record.phase_si = phase_from_rate(values_si, 1.0 / record.rate_hz, offset);
}

// Timestamps checked as by io::check_timing, after refusing a record whose sample rate changes:
// if more than 5 % of the intervals are off the median by over 1.5 x, the samples are not one rate with some dropped,
// and neither --allow-gaps nor --gaps split can make one equally spaced record of them.
io::TimingReport checked_timing(std::span<const double> time_s, const std::string& source,
                                const io::LineMap* lines, bool allow_gaps) {
  const io::TimingReport report = io::analyze_timing(time_s, source, lines);
  // Off-rate intervals: gaps (> 1.5 median) and intervals shorter than median / 1.5 (a faster
  // stretch when the median is the slower rate).
  std::size_t off_rate = report.gaps.size();
  for (std::size_t i = 1; i < time_s.size(); ++i) {
    const double dt = time_s[i] - time_s[i - 1];
    if (dt > 0.0 && dt * 1.5 < report.median_dt_s) ++off_rate;
  }
  if (off_rate > 10 && off_rate * 20 > report.n_samples) {
    auto rate_of = [&](std::size_t begin, std::size_t end) {
      std::vector<double> dt;
      for (std::size_t i = begin + 1; i < end; ++i) dt.push_back(time_s[i] - time_s[i - 1]);
      std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
      return 1.0 / dt[dt.size() / 2];
    };
    const std::size_t tenth = std::max<std::size_t>(time_s.size() / 10, 2);
    throw InputError(fmt::format(
        "{}: mixed sample rates: {} of {} intervals differ from the median {:.6g} s by more than 1.5 x "
        "({:.6g} Hz over the first tenth of the record, {:.6g} Hz over the last); fix: analyse each "
        "rate separately (split the file where the rate changes); imunoise never resamples",
        source, off_rate, report.n_samples - 1, report.median_dt_s, rate_of(0, tenth),
        rate_of(time_s.size() - tenth, time_s.size())));
  }
  return io::check_timing(time_s, source, lines, allow_gaps);
}

preprocess::PipelineOptions pipeline_options(const InputOptions& options) {
  preprocess::PipelineOptions p;
  p.skip = options.skip;
  p.detrend = options.detrend;
  p.outliers = options.outliers;
  p.split_gaps = options.gaps == "split";
  p.davar = options.davar;
  p.davar_window_s = options.davar_window_s;
  p.temperature = options.temperature;
  p.temperature_bin = options.temperature_bin;
  p.temperature_fit = options.temperature_fit;
  return p;
}

bool wants_preprocessing(const InputOptions& options) {
  return preprocess::wants_preprocessing(pipeline_options(options));
}

// The preprocessing steps on rate samples in SI (preprocess/pipeline.hpp). `gap_breaks`: first
// sample after each timestamp gap (for --gaps split). Each step says what it removed in
// record.preprocessing.
std::vector<double> preprocess_rates(const InputOptions& options, PhaseRecord& record, std::vector<double> values,
                                     std::vector<std::size_t> gap_breaks, std::vector<double> temperature = {}) {
  if (!wants_preprocessing(options)) return values;
  if (record.kind != InputKind::rate) {
    throw InputError(record.source + ": --skip, --detrend, --outliers, --gaps split and --davar work on "
                     "rate samples; fix: drop them, or pass rate input");
  }
  const std::string unit = record.unit_given ? std::string(si_unit_name(record.rate_unit.quantity)) : "input unit";
  auto result = preprocess::run_pipeline(pipeline_options(options), std::move(values),
                                         record.rate_hz, gap_breaks, std::move(temperature), record.source, unit);
  record.preprocessing.insert(record.preprocessing.end(), result.notes.begin(), result.notes.end());
  record.segments = std::move(result.segments);
  record.davar = std::move(result.davar);
  record.temperature_bins = std::move(result.temperature_bins);
  return std::move(result.values);
}

// Integrates preprocessed rate values; a split record keeps its rates and segments for the
// pooled estimators.
void finish_rates(PhaseRecord& record, std::vector<double> values) {
  if (record.segments.size() > 1) {
    record.n_samples = 0;
    for (const auto& seg : record.segments) record.n_samples += seg.size();
    record.rate_si = values;
  } else {
    if (record.segments.size() == 1) {
      const auto seg = record.segments.front();
      values = std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(seg.begin),
                                   values.begin() + static_cast<std::ptrdiff_t>(seg.end));
    }
    record.segments.clear();
    record.n_samples = values.size();
  }
  integrate_into(record, values);
}

std::vector<std::size_t> gap_breaks(const InputOptions& options, const PhaseRecord& record) {
  std::vector<std::size_t> breaks;
  if (options.gaps == "split" && record.timing) {
    for (const auto& g : record.timing->gaps) breaks.push_back(g.index);
  }
  return breaks;
}

bool gaps_allowed(const InputOptions& options) {
  if (!options.gaps.empty() && options.gaps != "fail" && options.gaps != "split") {
    throw InputError("--gaps " + options.gaps + " is not known; fix: pass fail or split");
  }
  if (options.gaps == "split" && options.allow_gaps) {
    throw InputError("--gaps split and --allow-gaps contradict each other; fix: drop one");
  }
  return options.allow_gaps || options.gaps == "split";
}

void load_binary(const InputOptions& options, PhaseRecord& record, double to_si) {
  if (!options.time_column.empty()) {
    throw InputError("--time-column is for text input; binary input needs --rate");
  }
  require_rate(record.rate_hz, record.source);
  const auto read = binary_options(options);
  if (wants_preprocessing(options)) {
    // Preprocessing needs the whole record (median, fits): read it all instead of streaming.
    if (options.gaps == "split") throw InputError(record.source + ": --gaps split needs timestamps; binary input has none");
    auto values = options.file == "-" ? io::read_binary_stream(std::cin, record.source, read)
                                      : io::read_binary_file(options.file, read);
    for (auto& v : values) v *= to_si;
    finish_rates(record, preprocess_rates(options, record, std::move(values), {}));
    return;
  }
  std::unique_ptr<io::BinaryReader> reader;
  if (options.file == "-") {
    reader = std::make_unique<io::BinaryReader>(std::cin, record.source, read);
  } else {
    reader = std::make_unique<io::BinaryReader>(options.file, read);
  }
  std::vector<double> chunk(kOffsetSamples);
  std::size_t got = reader->read(chunk);
  chunk.resize(got);
  for (auto& v : chunk) v *= to_si;
  if (record.kind == InputKind::angle) {
    // Angle input: samples are used as they are.
    if (const auto count = reader->record_count()) reserve_phase(record.phase_si, *count);
    record.phase_si.insert(record.phase_si.end(), chunk.begin(), chunk.end());
    chunk.resize(kOffsetSamples);
    while ((got = reader->read(chunk)) > 0) {
      for (std::size_t i = 0; i < got; ++i) record.phase_si.push_back(chunk[i] * to_si);
    }
    record.n_samples = record.phase_si.size();
    return;
  }
  if (const auto count = reader->record_count()) reserve_phase(record.phase_si, *count + 1);
  PhaseIntegrator integrator(1.0 / record.rate_hz, compensated_mean(chunk));
  std::size_t n = chunk.size();
  integrator.push(chunk, record.phase_si);
  chunk.resize(kOffsetSamples);
  while ((got = reader->read(chunk)) > 0) {
    for (std::size_t i = 0; i < got; ++i) chunk[i] *= to_si;
    integrator.push(std::span(chunk).first(got), record.phase_si);
    n += got;
  }
  record.n_samples = n;
}

void load_text(const InputOptions& options, PhaseRecord& record, double to_si) {
  io::TextReadOptions read;
  if (!options.column.empty()) read.column = io::parse_column_selector(options.column);
  if (!options.time_column.empty()) read.time_column = io::parse_column_selector(options.time_column);
  io::TextColumns columns = options.file == "-"
                                ? io::read_text_stream(std::cin, record.source, read)
                                : io::read_text_file(options.file, read);
  if (read.time_column) {
    record.timing = checked_timing(columns.time_s, record.source, &columns.lines, gaps_allowed(options));
    if (record.rate_hz > 0 && std::abs(record.timing->rate_hz / record.rate_hz - 1.0) > 0.01) {
      throw InputError(record.source + ": --rate " + fmt::format("{}", record.rate_hz) +
                       " Hz disagrees with the time column (" +
                       fmt::format("{:.6g}", record.timing->rate_hz) +
                       " Hz from the median interval); drop --rate or fix the time column");
    }
    if (record.rate_hz <= 0) record.rate_hz = record.timing->rate_hz;
  }
  require_rate(record.rate_hz, record.source);
  for (auto& v : columns.values) v *= to_si;
  if (wants_preprocessing(options)) {
    std::vector<double> temperature;
    if (!options.temperature.empty()) {
      if (options.file == "-") throw InputError("--temperature needs a file, not standard input");
      io::TextReadOptions t;
      t.column = io::parse_column_selector(options.temperature);
      temperature = io::read_text_file(options.file, t).values;
    }
    finish_rates(record, preprocess_rates(options, record, std::move(columns.values), gap_breaks(options, record),
                                          std::move(temperature)));
    return;
  }
  record.n_samples = columns.values.size();
  integrate_into(record, columns.values);
}

// A container recording (bag, MCAP, HDF5, EuRoC): one channel chosen by --column, its unit
// from the file unless --units is given (and then they must agree), the rate from the
// timestamps (checked like a text time column) or --rate.
void load_container(const InputOptions& options, PhaseRecord& record) {
  if (options.file == "-") throw InputError("--topic/--dataset need a file, not standard input");
  if (!options.binary.empty()) throw InputError(record.source + ": --binary is for raw sample files; drop it");
  if (!options.time_column.empty()) {
    throw InputError(record.source + ": --time-column is for text files; this file's timestamps are read "
                     "from the container (HDF5: --time-dataset)");
  }
  io::RecordingOptions read;
  read.topic = options.topic;
  read.dataset = options.dataset;
  read.time_dataset = options.time_dataset;
  const io::Recording recording = io::read_recording(options.file, read);
  record.format = std::string(io::format_name(recording.format));
  record.stream = recording.stream;
  if (options.column.empty() && recording.channels.size() != 1) {
    throw InputError(record.source + ": " + std::to_string(recording.channels.size()) +
                     " channels (" + recording.channel_list() + "); choose one with --column NAME");
  }
  const io::Channel& channel =
      options.column.empty() ? recording.channels.front() : recording.channel(options.column);
  record.channel = channel.name;
  Unit unit;
  if (channel.unit && !options.units.empty()) {
    unit = unit_of(options, record.kind, record.unit_given);
    if (unit.name != channel.unit->name) {
      throw InputError(record.source + ": channel " + channel.name + " is in " + channel.unit->name +
                       " according to the file, but --units says " + options.units + "; drop --units");
    }
  } else if (channel.unit) {
    if (record.kind != InputKind::rate) {
      throw InputError(record.source + ": channel " + channel.name + " holds rates (" + channel.unit->name +
                       "); drop --input angle");
    }
    unit = *channel.unit;
    record.unit_given = true;
  } else {
    unit = unit_of(options, record.kind, record.unit_given);
  }
  record.rate_unit = record.kind == InputKind::rate || !record.unit_given ? unit : derivative_unit(unit);
  if (!recording.time_s.empty()) {
    record.timing = checked_timing(recording.time_s, record.source, nullptr, gaps_allowed(options));
    if (record.rate_hz > 0 && std::abs(record.timing->rate_hz / record.rate_hz - 1.0) > 0.01) {
      throw InputError(record.source + ": --rate " + fmt::format("{}", record.rate_hz) +
                       " Hz disagrees with the file's timestamps (" +
                       fmt::format("{:.6g}", record.timing->rate_hz) + " Hz from the median interval); drop --rate");
    }
    if (record.rate_hz <= 0) record.rate_hz = record.timing->rate_hz;
  }
  require_rate(record.rate_hz, record.source);
  const double to_si = unit.to_si * value_scale(options);
  std::vector<double> values(channel.values);
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InputError(record.source + ": channel " + channel.name + " sample " + std::to_string(i) +
                       " is not finite (NaN or Inf); the analysis needs every sample");
    }
    values[i] *= to_si;
  }
  std::vector<double> temperature;
  if (!options.temperature.empty()) temperature = recording.channel(options.temperature).values;
  finish_rates(record, preprocess_rates(options, record, std::move(values), gap_breaks(options, record),
                                        std::move(temperature)));
}

bool is_container(const InputOptions& options) {
  if (!options.topic.empty() || !options.dataset.empty() || !options.time_dataset.empty()) return true;
  if (options.file == "-" || !options.binary.empty()) return false;
  return io::detect_container(options.file).has_value();
}

// The sample rate stated by the header of a text file written by `imunoise simulate`
// ("# imunoise simulate ..." then "# rate_hz R ..."); 0 when the file is not one.
double simulated_file_rate_hz(const std::string& path) {
  std::ifstream in(path);
  std::string first;
  std::string second;
  if (!std::getline(in, first) || first.rfind("# imunoise simulate", 0) != 0) return 0.0;
  if (!std::getline(in, second) || second.rfind("# rate_hz ", 0) != 0) return 0.0;
  try {
    const double rate_hz = std::stod(second.substr(10));
    return std::isfinite(rate_hz) && rate_hz > 0.0 ? rate_hz : 0.0;
  } catch (const std::exception&) {
    return 0.0;
  }
}

}  // namespace

void add_input_options(CLI::App& command, InputOptions& options) {
  command.add_option("file", options.file, "input file (text, raw binary, ROS 1 bag, MCAP, HDF5 or EuRoC CSV); - for standard input")
      ->required();
  command.add_option("--rate", options.rate_hz, "sample rate (Hz)");
  command.add_option("--input", options.input, "what the samples are: rate (freq) or angle (phase)")
      ->capture_default_str();
  command.add_option("--units", options.units,
                     "unit of the values (after --scale), e.g. deg/s, rad/s, deg/h, m/s^2, g; "
                     "angle input: deg, rad");
  command.add_option("--column", options.column, "column to read: 0-based index or header name; "
                                                  "binary: channel index");
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

PhaseRecord load_phase(const InputOptions& options) {
  PhaseRecord record;
  record.source = source_name(options.file);
  if (options.file != "-" && !std::filesystem::exists(options.file)) {
    throw InputError(options.file + ": no such file; check the path");
  }
  record.kind = parse_input_kind(options.input);
  record.rate_hz = options.rate_hz;
  if (is_container(options)) {
    load_container(options, record);
    if (record.n_samples == 0) throw InputError(record.source + ": no samples");
    require_finite_phase(record);
    return record;
  }
  record.format = is_binary(options) ? "binary" : "text";
  const Unit unit = unit_of(options, record.kind, record.unit_given);
  // Angle input's rate unit is the derivative of its unit, given or not: unitless phase (clock
  // data in seconds) has the neutral time unit, whose rate is dimensionless, so the estimators
  // reported in the angle unit (tdev, ttotdev, mtie, tierms) convert back through it.
  record.rate_unit = record.kind == InputKind::rate ? unit : derivative_unit(unit);
  const double to_si = unit.to_si * value_scale(options);
  if (is_binary(options)) {
    load_binary(options, record, to_si);
  } else {
    if (!(record.rate_hz > 0.0) && options.time_column.empty() && options.file != "-") {
      record.rate_hz = simulated_file_rate_hz(options.file);
      if (record.rate_hz > 0.0) {
        fmt::print(stderr, "imunoise: {}: rate {:g} Hz from the file's imunoise simulate header "
                           "(--rate overrides)\n", record.source, record.rate_hz);
      }
    }
    load_text(options, record, to_si);
  }
  if (record.n_samples == 0) throw InputError(record.source + ": no samples");
  require_finite_phase(record);
  return record;
}

RecordPlan plan_record(const InputOptions& options) {
  RecordPlan plan;
  PhaseRecord& record = plan.meta;
  record.source = source_name(options.file);
  if (options.file != "-" && !std::filesystem::exists(options.file)) {
    throw InputError(options.file + ": no such file; check the path");
  }
  record.kind = parse_input_kind(options.input);
  record.rate_hz = options.rate_hz;
  const Unit unit = unit_of(options, record.kind, record.unit_given);
  record.rate_unit = record.kind == InputKind::rate || !record.unit_given ? unit : derivative_unit(unit);
  plan.to_si = unit.to_si * value_scale(options);
  plan.binary = is_binary(options);
  if (plan.binary) {
    if (!options.time_column.empty()) {
      throw InputError("--time-column is for text input; binary input needs --rate");
    }
    require_rate(record.rate_hz, record.source);
    plan.read = binary_options(options);
  }
  return plan;
}

std::string unit_label(const PhaseRecord& record, bool integrated) {
  if (!record.unit_given) {
    const bool angle = record.kind == InputKind::angle;
    if (integrated) return angle ? "input unit" : "input unit*s";
    return angle ? "input unit/s" : "input unit";
  }
  return integrated ? integral_unit(record.rate_unit).name : record.rate_unit.name;
}

}  // namespace imunoise::cli
