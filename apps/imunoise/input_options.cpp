#include "input_options.hpp"

#include <sys/mman.h>

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
#include "imunoise/io/text_reader.hpp"
#include "imunoise/phase.hpp"

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

void load_binary(const InputOptions& options, PhaseRecord& record, double to_si) {
  if (!options.time_column.empty()) {
    throw InputError("--time-column is for text input; binary input needs --rate");
  }
  require_rate(record.rate_hz, record.source);
  const auto read = binary_options(options);
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
    record.timing = io::check_timing(columns.time_s, record.source, &columns.lines, options.allow_gaps);
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
  record.n_samples = columns.values.size();
  integrate_into(record, columns.values);
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
  command.add_option("file", options.file, "input file (text or raw binary); - for standard input")
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
  const Unit unit = unit_of(options, record.kind, record.unit_given);
  record.rate_unit = record.kind == InputKind::rate || !record.unit_given ? unit : derivative_unit(unit);
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
