#include "imunoise/load/load.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <new>
#include <span>
#include <thread>

#include <fmt/core.h>

#include "imunoise/comma_list.hpp"
#include "imunoise/error.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/io/recording.hpp"
#include "imunoise/io/text_reader.hpp"
#include "imunoise/load/integrate.hpp"
#include "imunoise/phase.hpp"
#include "../core/prefaulted.hpp"

namespace imunoise::load {
namespace {

std::string source_name(const std::string& file) {
  return file == "-" ? "standard input" : file;
}

// A neutral unit for records whose unit was not given: no conversion, labelled at the edges.
Unit unit_of(const LoadOptions& options, InputKind kind, bool& given) {
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

double value_scale(const LoadOptions& options) {
  if (!std::isfinite(options.scale) || options.scale == 0.0) {
    throw InputError("--scale must be finite and non-zero, got " + fmt::format("{}", options.scale));
  }
  if (options.sensitivity != 0.0) {
    if (!std::isfinite(options.sensitivity)) throw InputError("--sensitivity must be finite");
    return options.scale / options.sensitivity;
  }
  return options.scale;
}

// Rate samples decoded, integrated and checked per block after the first: 64 KB, in L2.
constexpr std::size_t kStreamBlockSamples = 8192;

// Reserves the phase array of a long record (its largest array) in huge pages and returns a
// thread that faults them in on the other core ahead of the integrator that writes them: the
// kernel zeroes every fresh page, and that, not the integration, was most of a long binary
// load (perf: clear_page ~50 % of `dev` on 1e7 f64 samples). The thread only asks the kernel to
// populate the memory (no stores), so it does not race with the writer; joined on return.
std::jthread reserve_phase(std::vector<double>& phase, std::size_t count) {
  phase.reserve(count);
  constexpr std::size_t huge = std::size_t{2} << 20;
  const std::size_t advised = detail::advise_huge_pages(phase.data(), count * sizeof(double));
  if (advised < 8 * huge || std::thread::hardware_concurrency() < 2) return {};
  // The small pages before the first and after the last huge page too (up to 4 MB, ~600 page
  // faults of the writer on 1e7 samples otherwise: tens of microseconds each on a VM).
  const double* data = phase.data();
  return std::jthread([data, count] { detail::populate_pages(data, count * sizeof(double)); });
}

struct FreeDeleter {
  void operator()(double* p) const { std::free(p); }
};

// An uninitialised buffer of `count` samples; from 2 MB on in transparent huge pages. The
// first block (the rate offset's 1e6 samples, 8 MB) in 4 KB pages took 2,048 page faults on
// its first write, and on a virtual machine a fault is an exit to the hypervisor (26 us each on
// the 2-vCPU VM of 2026-12-05: ~50 ms of `dev` on 1e7 samples, docs/performance.md).
std::unique_ptr<double[], FreeDeleter> read_buffer(std::size_t count) {
  constexpr std::size_t huge = std::size_t{2} << 20;
  const std::size_t bytes = count * sizeof(double);
  void* p = nullptr;
  if (bytes >= huge) {
    const std::size_t rounded = (bytes + huge - 1) / huge * huge;
    p = std::aligned_alloc(huge, rounded);
    if (p != nullptr) detail::advise_huge_pages(p, rounded);
  } else {
    p = std::malloc(bytes);
  }
  if (p == nullptr) throw std::bad_alloc();
  return std::unique_ptr<double[], FreeDeleter>(static_cast<double*>(p));
}

bool is_binary(const LoadOptions& options) {
  return !options.binary.empty() ||
         (options.file != "-" && io::binary_format_from_extension(options.file).has_value());
}

io::BinaryReadOptions binary_options(const LoadOptions& options) {
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
// from: the first sample not yet checked (a streamed phase is checked block by block in cache).
void require_finite_phase(const Record& record, std::size_t from = 0) {
  const std::span<const double> unchecked = std::span<const double>(record.phase_si).subspan(from);
  const unsigned threads = unchecked.size() > kStreamBlockSamples ? 0 : 1;
  if (const std::size_t k = from + first_non_finite(unchecked, threads); k < record.phase_si.size()) {
    throw InputError(record.source + ": the integral of the samples overflows at sample " +
                     std::to_string(k) + "; check --units, --scale and --sensitivity");
  }
}

// Rate or angle samples (already in SI) into the record's phase array.
void integrate_into(Record& record, std::span<const double> values_si) {
  if (record.kind == InputKind::angle) {
    record.phase_si.assign(values_si.begin(), values_si.end());
    return;
  }
  record.phase_si = integrate_rate(values_si, record.rate_hz);
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

bool wants_preprocessing(const LoadOptions& options) {
  return preprocess::wants_preprocessing(pipeline_options(options));
}

std::vector<std::size_t> gap_breaks(const LoadOptions& options, const Record& record) {
  std::vector<std::size_t> breaks;
  if (options.gaps == "split" && record.timing) {
    for (const auto& g : record.timing->gaps) breaks.push_back(g.index);
  }
  return breaks;
}

bool gaps_allowed(const LoadOptions& options) {
  if (!options.gaps.empty() && options.gaps != "fail" && options.gaps != "split") {
    throw InputError("--gaps " + options.gaps + " is not known; fix: pass fail or split");
  }
  if (options.gaps == "split" && options.allow_gaps) {
    throw InputError("--gaps split and --allow-gaps contradict each other; fix: drop one");
  }
  return options.allow_gaps || options.gaps == "split";
}

void load_binary(const LoadOptions& options, Record& record, double to_si) {
  if (!options.time_column.empty()) {
    throw InputError("--time-column is for text input; binary input needs --rate");
  }
  require_rate(record.rate_hz, record.source);
  const auto read = binary_options(options);
  if (wants_preprocessing(options) || options.keep_rates) {
    // Preprocessing needs the whole record (median, fits): read it all instead of streaming.
    if (options.gaps == "split") throw InputError(record.source + ": --gaps split needs timestamps; binary input has none");
    auto values = options.file == "-" ? io::read_binary_stream(std::cin, record.source, read)
                                      : io::read_binary_file(options.file, read);
    for (auto& v : values) v *= to_si;
    record = finish_rates(std::move(record), std::move(values), pipeline_options(options), {}, {},
                          options.keep_rates);
    return;
  }
  // The unit factor goes into the reader's one multiplication (read.scale is 1 here, so the
  // values are the same bits as scaling afterwards), and an overflow is named there by record.
  auto streamed = read;
  streamed.scale = read.scale * to_si;
  std::unique_ptr<io::BinaryReader> reader;
  if (options.file == "-") {
    reader = std::make_unique<io::BinaryReader>(std::cin, record.source, streamed);
  } else {
    reader = std::make_unique<io::BinaryReader>(options.file, streamed);
  }
  // The first block holds the samples of the rate offset; the read buffer is no larger than the
  // record (a 2,000-sample file zeroed 8 MB of fresh pages, most of such a run's time) and left
  // uninitialised: the reader writes every element it returns before anything reads it.
  const std::size_t capacity =
      std::max<std::size_t>(1, std::min(kRateOffsetSamples, reader->record_count().value_or(kRateOffsetSamples)));
  const auto storage = read_buffer(capacity);
  const std::span<double> buffer(storage.get(), capacity);
  const std::span<double> first = buffer.first(reader->read(buffer));
  // After it, blocks small enough to stay in L2 between decoding, integrating and checking:
  // 8 MB blocks made each of those stages a pass through memory (perf, 1e7 f64 samples).
  const std::span<double> block = buffer.first(std::min(capacity, kStreamBlockSamples));
  std::jthread populate;
  if (record.kind == InputKind::angle) {
    // Angle input: samples are used as they are.
    if (const auto count = reader->record_count()) populate = reserve_phase(record.phase_si, *count);
    record.phase_si.insert(record.phase_si.end(), first.begin(), first.end());
    for (std::size_t got; (got = reader->read(block)) > 0;) {
      record.phase_si.insert(record.phase_si.end(), block.begin(), block.begin() + static_cast<std::ptrdiff_t>(got));
    }
    record.n_samples = record.phase_si.size();
    return;  // the reader has checked every sample
  }
  if (const auto count = reader->record_count()) populate = reserve_phase(record.phase_si, *count + 1);
  PhaseIntegrator integrator(1.0 / record.rate_hz, rate_offset(first));
  integrator.push(first, record.phase_si);
  require_finite_phase(record, 0);
  std::size_t n = first.size();
  for (std::size_t got; (got = reader->read(block)) > 0; n += got) {
    const std::size_t from = record.phase_si.size();
    integrator.push(block.first(got), record.phase_si);
    require_finite_phase(record, from);  // the streamed phase bypasses finish_rates
  }
  record.n_samples = n;
}

void load_text(const LoadOptions& options, Record& record, double to_si) {
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
  std::vector<double> temperature;
  if (!options.temperature.empty()) {
    if (options.file == "-") throw InputError("--temperature needs a file, not standard input");
    io::TextReadOptions t;
    t.column = io::parse_column_selector(options.temperature);
    temperature = io::read_text_file(options.file, t).values;
  }
  const auto breaks = gap_breaks(options, record);
  record = finish_rates(std::move(record), std::move(columns.values), pipeline_options(options), breaks,
                        std::move(temperature), options.keep_rates);
}

// A container recording (ROS 1/2 bag, MCAP, ULog, HDF5, EuRoC): one channel chosen by --column, its unit
// from the file unless --units is given (and then they must agree), the rate from the
// timestamps (checked like a text time column) or --rate.
void load_container(const LoadOptions& options, Record& record) {
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
  record.notes.insert(record.notes.end(), recording.notes.begin(), recording.notes.end());
  const std::vector<double>& time_s = recording.times(channel);  // a PX4 sensor instance has its own
  if (!time_s.empty()) {
    try {
      record.timing = checked_timing(time_s, record.source, nullptr, gaps_allowed(options));
    } catch (const InputError& e) {
      // A gap that the reader can explain (a PX4 logger dropout) says so.
      if (recording.notes.empty()) throw;
      std::string message = e.what();
      for (const auto& note : recording.notes) message += "\n  note: " + note;
      throw InputError(message);
    }
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
  const auto breaks = gap_breaks(options, record);
  record = finish_rates(std::move(record), std::move(values), pipeline_options(options), breaks,
                        std::move(temperature), options.keep_rates);
}

bool is_container(const LoadOptions& options) {
  if (!options.topic.empty() || !options.dataset.empty() || !options.time_dataset.empty()) return true;
  if (options.file == "-" || !options.binary.empty()) return false;
  return io::detect_container(options.file).has_value();
}

// The sample rate stated by the header of a text file written by `imunoise simulate`
// ("# imunoise simulate ..." then "# rate_hz R ..."); 0 when the file is not one.
struct SimulateHeader {
  double rate_hz = 0.0;      ///< 0 when the file is not one
  std::string output_unit;   ///< "" when not stated
};

SimulateHeader simulated_file_header(const std::string& path) {
  SimulateHeader h;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line.rfind("# imunoise simulate", 0) != 0) return h;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) {
    if (line.rfind("# rate_hz ", 0) == 0) {
      try {
        const double rate_hz = std::stod(line.substr(10));
        if (std::isfinite(rate_hz) && rate_hz > 0.0) h.rate_hz = rate_hz;
      } catch (const std::exception&) {
      }
    }
    const auto pos = line.find("output unit ");
    if (pos != std::string::npos) {
      const auto rest = line.substr(pos + 12);
      h.output_unit = rest.substr(0, rest.find_first_of(";, "));
    }
  }
  return h;
}

// A simulated file states the unit of its values; --units must not say another.
void check_stated_unit(const SimulateHeader& header, const LoadOptions& options, const std::string& source) {
  if (header.output_unit.empty() || options.units.empty()) return;
  Unit stated;
  try {
    stated = parse_unit(header.output_unit);
  } catch (const InputError&) {
    return;  // a unit that is not a rate unit (volts): nothing to compare
  }
  if (stated.name != parse_unit(options.units).name) {
    throw InputError(fmt::format("{} is in {} (its header says so) but --units is {}: pass --units {}",
                                 source, header.output_unit, options.units, header.output_unit));
  }
}

// The fields of a text file's first non-comment line (its header, or its first row).
std::vector<std::string> first_line_fields(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open the file; check the path");
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    break;
  }
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  const auto hash = line.find('#');
  if (hash != std::string::npos) line.erase(hash);
  return io::split_fields(line);
}

// Header names that are timestamps, not sensor values (case-insensitive).
bool is_time_name(std::string name) {
  for (auto& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* t : {"t", "t_s", "t_ns", "time", "time_s", "time_ns", "timestamp", "timestamp_s",
                        "timestamp_ns", "stamp", "#timestamp", "#timestamp [ns]", "timestamp [ns]"}) {
    if (name == t) return true;
  }
  return false;
}

// A header column named like a timestamp, when the first line of the text file is a header.
std::optional<std::string> timestamp_column(const std::string& file) {
  const auto fields = first_line_fields(file);
  bool header = false;
  for (const auto& f : fields) header = header || !io::parse_number(f).has_value();
  if (!header) return std::nullopt;
  for (const auto& f : fields) {
    if (is_time_name(f)) return f;
  }
  return std::nullopt;
}

}  // namespace

preprocess::PipelineOptions pipeline_options(const LoadOptions& options) {
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

Record finish_rates(Record record, std::vector<double> values, const preprocess::PipelineOptions& options,
                    std::span<const std::size_t> gap_breaks, std::vector<double> temperature,
                    bool keep_rates) {
  if (preprocess::wants_preprocessing(options)) {
    if (record.kind != InputKind::rate) {
      throw InputError(record.source + ": --skip, --detrend, --outliers, --gaps split and --davar work on "
                       "rate samples; fix: drop them, or pass rate input");
    }
    const std::string unit =
        record.unit_given ? std::string(si_unit_name(record.rate_unit.quantity)) : "input unit";
    auto result = preprocess::run_pipeline(options, std::move(values), record.rate_hz, gap_breaks,
                                           std::move(temperature), record.source, unit);
    record.preprocessing.insert(record.preprocessing.end(), result.notes.begin(), result.notes.end());
    record.segments = std::move(result.segments);
    record.davar = std::move(result.davar);
    record.temperature_bins = std::move(result.temperature_bins);
    values = std::move(result.values);
  }
  // A split record keeps its rates and segments for the pooled estimators; one segment is
  // simply the record.
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
    if (keep_rates) record.rate_si = values;
  }
  integrate_into(record, values);
  require_finite_phase(record);
  return record;
}

Record load(const LoadOptions& options) {
  Record record;
  record.source = source_name(options.file);
  if (options.file != "-" && !std::filesystem::exists(options.file)) {
    throw InputError(options.file + ": no such file; check the path");
  }
  record.kind = parse_input_kind(options.input);
  record.rate_hz = options.rate_hz;
  if (is_container(options)) {
    load_container(options, record);
    if (record.n_samples == 0) throw InputError(record.source + ": no samples");
    record.name = record.source;
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
    const SimulateHeader header = options.file == "-" ? SimulateHeader{} : simulated_file_header(options.file);
    check_stated_unit(header, options, record.source);
    if (!(record.rate_hz > 0.0) && options.time_column.empty()) {
      record.rate_hz = header.rate_hz;
      if (record.rate_hz > 0.0) {
        record.notes.push_back(fmt::format("{}: rate {:g} Hz from the file's imunoise simulate header "
                                           "(--rate overrides)", record.source, record.rate_hz));
      }
    }
    LoadOptions text = options;
    if (!(record.rate_hz > 0.0) && options.time_column.empty() && options.file != "-") {
      if (const auto time_column = timestamp_column(options.file)) {
        record.notes.push_back(record.source + ": column '" + *time_column + "' is read as the timestamps "
                               "(its name says so); pass --time-column to choose another, or --rate");
        text.time_column = *time_column;
      }
    }
    load_text(text, record, to_si);
  }
  // Every path has checked the phase for overflow: finish_rates, or the binary stream.
  if (record.n_samples == 0) throw InputError(record.source + ": no samples");
  record.name = record.source;
  return record;
}

RecordPlan plan_record(const LoadOptions& options) {
  RecordPlan plan;
  Record& record = plan.meta;
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

namespace {

std::string stem_of(const std::string& file) {
  if (file == "-") return "stdin";
  return std::filesystem::path(file).stem().string();
}

// The name of a channel in the report: its column or channel name, prefixed with the file's
// stem when several files are studied; the stem alone for a file of one unnamed channel.
std::string channel_name(const std::string& file, const std::string& column, std::size_t n_files,
                         std::size_t n_columns, bool named, bool binary) {
  if (n_columns == 1 && column.empty()) return stem_of(file);
  const bool several = n_columns > 1;
  const std::string label = named ? column : (binary ? "ch" + column : "col" + column);
  if (n_files == 1) return several || named ? label : stem_of(file);
  return several ? stem_of(file) + ":" + label : stem_of(file);
}

}  // namespace

std::vector<ChannelPlan> plan_channels(std::span<const std::string> files, const std::string& columns_list,
                                       const std::string& names_list, const LoadOptions& shared, bool keep_going,
                                       const std::function<void(const std::string&, const std::string&)>& failed) {
  std::vector<ChannelPlan> plan;
  const auto wanted = split_comma_list(columns_list);
  for (const auto& file : files) {
    LoadOptions base = shared;
    base.file = file;
    std::vector<std::string> columns = wanted;
    std::string base_note;
    bool named = !wanted.empty();
    bool binary = false;
    if (columns.empty()) {
      try {
        auto found = file_channels(base);
        columns = std::move(found.names);
        named = found.named;
        binary = found.binary;
        if (!found.time_column.empty()) base.time_column = found.time_column;
        if (!found.note.empty()) base_note = found.note;
      } catch (const InputError& e) {
        if (!keep_going) throw;
        failed(file, e.what());
        continue;
      }
    } else {
      binary = !base.binary.empty() ||
               (file != "-" && io::binary_format_from_extension(file).has_value());
    }
    for (const auto& column : columns) {
      ChannelPlan ch{base, channel_name(file, column, files.size(), columns.size(), named, binary), base_note};
      ch.options.column = column;
      base_note.clear();
      plan.push_back(std::move(ch));
    }
  }
  const auto names = split_comma_list(names_list);
  if (!names.empty()) {
    if (names.size() != plan.size()) {
      throw InputError(fmt::format("--names gives {} names for {} channels; fix: one name per "
                                   "channel, in file and column order", names.size(), plan.size()));
    }
    for (std::size_t i = 0; i < plan.size(); ++i) plan[i].name = names[i];
  }
  const auto units = split_comma_list(shared.units);
  if (units.size() > 1 && units.size() != plan.size()) {
    throw InputError(fmt::format("--units gives {} units for {} channels; fix: one unit for all, "
                                 "or one per channel in file and column order",
                                 units.size(), plan.size()));
  }
  for (std::size_t i = 0; i < plan.size(); ++i) {
    plan[i].options.units = units.empty() ? std::string() : units.size() == 1 ? units[0] : units[i];
  }
  return plan;
}

FileChannels file_channels(const LoadOptions& options) {
  FileChannels out;
  if (options.file == "-") {
    out.names.push_back("");
    return out;
  }
  if (is_container(options)) {
    if (!std::filesystem::exists(options.file)) throw InputError(options.file + ": no such file; check the path");
    io::RecordingOptions read;
    read.topic = options.topic;
    read.dataset = options.dataset;
    read.time_dataset = options.time_dataset;
    for (const auto& channel : io::read_recording(options.file, read).channels) {
      if (channel.name != options.temperature) out.names.push_back(channel.name);
    }
    out.named = true;
    return out;
  }
  if (is_binary(options)) {
    for (std::size_t c = 0; c < options.channels; ++c) out.names.push_back(std::to_string(c));
    out.binary = true;
    return out;
  }
  const auto fields = first_line_fields(options.file);
  for (const auto& f : fields) out.named = out.named || !io::parse_number(f).has_value();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string name = out.named ? fields[i] : std::to_string(i);
    const std::string index = std::to_string(i);
    if (!options.time_column.empty() && (options.time_column == name || options.time_column == index)) continue;
    if (!options.temperature.empty() && (options.temperature == name || options.temperature == index)) continue;
    if (out.named && options.time_column.empty() && is_time_name(name)) {
      if (out.time_column.empty() && !(options.rate_hz > 0.0)) {
        out.time_column = name;
        out.note = options.file + ": column '" + name + "' is read as the timestamps (its name says "
                   "so); pass --time-column to choose another, or --rate to use none";
      } else if (out.note.empty()) {
        out.note = options.file + ": column '" + name + "' looks like timestamps and is not analysed "
                   "(--rate was given); pass --columns to analyse it anyway";
      }
      continue;
    }
    out.names.push_back(name);
  }
  return out;
}

BinaryLayout binary_layout(const RecordPlan& plan, const std::string& path, bool with_offset) {
  io::BinaryReader reader(path, plan.read);
  BinaryLayout layout;
  layout.records = *reader.record_count();
  if (with_offset && plan.meta.kind == InputKind::rate) {
    std::vector<double> first(std::min(kRateOffsetSamples, layout.records));
    reader.read(first);
    for (auto& v : first) v *= plan.to_si;
    layout.rate_offset_si = rate_offset(first);
  }
  return layout;
}

std::vector<double> read_phase_slice(const RecordPlan& plan, const std::string& path, std::size_t first,
                                     std::size_t count, double rate_offset_si) {
  io::BinaryReader reader(path, plan.read);
  std::vector<double> values(count);
  reader.seek(first);
  if (reader.read(values) != count) throw InputError(path + ": short read at record " + std::to_string(first));
  for (auto& v : values) v *= plan.to_si;
  std::vector<double> phase;
  if (plan.meta.kind == InputKind::rate) {
    phase.reserve(count + 1);
    PhaseIntegrator integrator(1.0 / plan.meta.rate_hz, rate_offset_si);
    integrator.push(values, phase);
  } else {
    phase = std::move(values);
  }
  if (const std::size_t i = first_non_finite(phase, 0); i < phase.size()) {
    throw InputError(plan.meta.source + ": the integral of the samples overflows near sample " +
                     std::to_string(first + i) + "; check --units, --scale and --sensitivity");
  }
  return phase;
}

std::vector<Record> load_channels(std::span<const ChannelPlan> plan, bool keep_going,
                                  const std::function<void(const std::string& file, const std::string& error)>& skipped,
                                  const std::function<void(std::size_t)>& before) {
  std::vector<Record> records;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (before) before(i);
    try {
      Record record = load(plan[i].options);
      record.name = plan[i].name;
      if (!plan[i].note.empty()) record.notes.insert(record.notes.begin(), "note: " + plan[i].note);
      records.push_back(std::move(record));
    } catch (const InputError& e) {
      if (!keep_going) {
        if (plan.size() > 1) throw InputError(std::string(e.what()) + " (pass --keep-going to study the other inputs without it)");
        throw;
      }
      if (skipped) skipped(plan[i].options.file, e.what());
    }
  }
  return records;
}

}  // namespace imunoise::load
