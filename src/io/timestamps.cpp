#include "imunoise/io/timestamps.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/io/text_reader.hpp"

namespace imunoise::io {
namespace {

// A gap is an interval longer than this many median intervals: halfway between one interval
// (a regular sample) and two (one sample missing), so jitter below 50 % is never a gap.
constexpr double gap_threshold = 1.5;

// Integer nanoseconds are recognised above this magnitude (see looks_like_nanoseconds).
constexpr std::int64_t nanosecond_threshold = 1'000'000'000'000'000;

bool is_digit(char c) { return c >= '0' && c <= '9'; }

std::string number_text(double value) { return fmt::format("{:.10g}", value); }

// "file:123: sample 120" when the line is known, else "file: sample 120".
std::string where(std::string_view source, std::optional<std::size_t> line, std::size_t index) {
  std::string text(source);
  text += ":";
  if (line && *line != 0) text += std::to_string(*line) + ":";
  return text + " sample " + std::to_string(index);
}

std::optional<std::size_t> line_of(const LineMap* lines, std::size_t index) {
  if (lines == nullptr) return std::nullopt;
  const std::size_t line = lines->line_of(index);
  return line == 0 ? std::nullopt : std::optional<std::size_t>(line);
}

double median_of(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return lower + (upper - lower) / 2.0;
}

std::size_t missing_samples(double dt_s, double median_dt_s) {
  const double intervals = std::round(dt_s / median_dt_s);
  // Clamp so that an absurd gap (e.g. a clock jump of years) cannot overflow the conversion.
  constexpr double max_count = 1e18;
  return static_cast<std::size_t>(std::min(intervals, max_count)) - 1;
}

}  // namespace

std::optional<SplitTime> parse_split_time(std::string_view text) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  const char* p = begin;
  const bool negative = p != end && *p == '-';
  if (p != end && (*p == '-' || *p == '+')) ++p;
  const char* digits = p;
  while (p != end && is_digit(*p)) ++p;
  const char* digits_end = p;
  bool plain = digits != digits_end;
  if (plain && p != end) {  // only a '.' and more digits may follow
    plain = *p == '.';
    if (plain) {
      ++p;
      while (p != end && is_digit(*p)) ++p;
      plain = p == end;
    }
  }
  if (plain) {
    std::int64_t whole = 0;
    const auto result = std::from_chars(digits, digits_end, whole);
    if (result.ec == std::errc()) {
      double fraction = 0.0;
      if (digits_end != end && digits_end + 1 != end) {
        fraction = parse_number(std::string_view(digits_end, static_cast<std::size_t>(end - digits_end))).value_or(0.0);
      }
      if (negative) {
        whole = -whole;
        fraction = -fraction;
      }
      return SplitTime{whole, fraction, digits_end == end};
    }
    // More integer digits than an int64 holds: fall through to a plain double.
  }
  const std::optional<double> value = parse_number(text);
  if (!value) return std::nullopt;
  return SplitTime{0, *value, false};
}

bool is_finite(const SplitTime& time) { return std::isfinite(time.fraction); }

bool looks_like_nanoseconds(std::span<const SplitTime> times) {
  if (times.empty()) return false;
  const bool all_integer =
      std::all_of(times.begin(), times.end(), [](const SplitTime& t) { return t.integer; });
  const std::int64_t first = times.front().whole;
  return all_integer && (first > nanosecond_threshold || first < -nanosecond_threshold);
}

std::vector<double> relative_seconds(std::span<const SplitTime> times, double unit_to_s) {
  std::vector<double> out;
  out.reserve(times.size());
  if (times.empty()) return out;
  const SplitTime& origin = times.front();
  // For sub-second units (ms, us, ns) divide by the exact integer count per second instead of
  // multiplying by the inexact 1e-9: the result is then correctly rounded, so 5000001 ns gives
  // exactly the double nearest 0.005000001 s.
  const double per_s = std::round(1.0 / unit_to_s);
  const bool divide = unit_to_s < 1.0 && std::abs(per_s * unit_to_s - 1.0) < 1e-12;
  for (const SplitTime& t : times) {
    // The integer parts are subtracted in integers: that is where epoch times lose precision
    // as doubles. If the difference itself overflows, the values span > 9e18 units and double
    // precision is all that is meaningful anyway.
    std::int64_t whole_difference = 0;
    const double whole =
        __builtin_sub_overflow(t.whole, origin.whole, &whole_difference)
            ? static_cast<double>(t.whole) - static_cast<double>(origin.whole)
            : static_cast<double>(whole_difference);
    const double elapsed = whole + (t.fraction - origin.fraction);
    out.push_back(divide ? elapsed / per_s : elapsed * unit_to_s);
  }
  return out;
}

std::vector<double> relative_seconds_from_ns(std::span<const std::int64_t> times_ns) {
  std::vector<SplitTime> split;
  split.reserve(times_ns.size());
  for (std::int64_t t : times_ns) split.push_back(SplitTime{t, 0.0, true});
  return relative_seconds(split, 1e-9);
}

TimingReport analyze_timing(std::span<const double> time_s, std::string_view source,
                            const LineMap* lines) {
  const std::size_t n = time_s.size();
  if (n < 2) {
    throw InputError(std::string(source) + ": " + std::to_string(n) +
                     " timestamp(s); at least 2 are needed to derive a sample rate; fix: give "
                     "a longer record, or pass --rate instead of a time column");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(time_s[i])) {
      throw InputError(where(source, line_of(lines, i), i) + ": time is " +
                       number_text(time_s[i]) + "; fix: repair or remove the row");
    }
  }
  std::vector<double> dt_s(n - 1);
  for (std::size_t i = 1; i < n; ++i) dt_s[i - 1] = time_s[i] - time_s[i - 1];

  TimingReport report;
  report.n_samples = n;
  report.median_dt_s = median_of(dt_s);
  report.duration_s = time_s[n - 1] - time_s[0];
  // A median of +inf (times near the double range) would give a rate of 0 Hz; a subnormal one
  // an infinite rate. Neither is a sample rate.
  const double rate_hz = 1.0 / report.median_dt_s;
  if (!(report.median_dt_s > 0.0) || !std::isfinite(report.median_dt_s) || !std::isfinite(rate_hz)) {
    throw InputError(std::string(source) + ": the median interval between timestamps is " +
                     number_text(report.median_dt_s) +
                     " s, so no positive sample rate follows; fix: check the time column "
                     "(--time-column) and its unit, sort the rows by time and remove duplicates");
  }
  report.rate_hz = rate_hz;

  // Welford's running mean and variance of the regular intervals.
  std::size_t regular = 0;
  double mean = 0.0;
  double sum_squares = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double dt = dt_s[i - 1];
    if (dt <= 0.0) {
      report.disorder.push_back({i, line_of(lines, i), time_s[i] - time_s[0], time_s[i - 1] - time_s[0]});
    } else if (dt > gap_threshold * report.median_dt_s) {
      const std::size_t missing = missing_samples(dt, report.median_dt_s);
      report.gaps.push_back({i, line_of(lines, i), dt, missing});
      report.missing_samples += missing;
    } else {
      ++regular;
      const double delta = dt - mean;
      mean += delta / static_cast<double>(regular);
      sum_squares += delta * (dt - mean);
      report.jitter_rel_max =
          std::max(report.jitter_rel_max, std::abs(dt - report.median_dt_s) / report.median_dt_s);
    }
  }
  if (regular >= 2) {
    report.jitter_rel_std =
        std::sqrt(sum_squares / static_cast<double>(regular - 1)) / report.median_dt_s;
  }
  return report;
}

void require_ordered(const TimingReport& report, std::string_view source) {
  if (report.disorder.empty()) return;
  const TimeDisorder& first = report.disorder.front();
  const char* kind = first.time_s == first.previous_time_s ? "duplicates" : "is before";
  throw InputError(where(source, first.line, first.index) + ": its time " +
                   number_text(first.time_s) + " s " + kind + " the previous sample's " +
                   number_text(first.previous_time_s) + " s (times relative to the first sample); " +
                   std::to_string(report.disorder.size()) +
                   " sample(s) are out of order or duplicated; fix: sort the file by time and "
                   "remove duplicate rows");
}

void require_no_gaps(const TimingReport& report, std::string_view source) {
  if (report.gaps.empty()) return;
  const TimeGap& first = report.gaps.front();
  throw InputError(where(source, first.line, first.index) + ": time gap of " +
                   number_text(first.duration_s) + " s before this sample (about " +
                   std::to_string(first.missing_samples) + " missing at " +
                   number_text(report.rate_hz) + " Hz); " + std::to_string(report.gaps.size()) +
                   " gap(s) in total, " + std::to_string(report.missing_samples) +
                   " missing sample(s); fix: split the record at the gap, or pass --allow-gaps "
                   "to treat samples as equally spaced; imunoise never interpolates");
}

TimingReport check_timing(std::span<const double> time_s, std::string_view source,
                          const LineMap* lines, bool allow_gaps) {
  TimingReport report = analyze_timing(time_s, source, lines);
  require_ordered(report, source);
  if (!allow_gaps) require_no_gaps(report, source);
  return report;
}

}  // namespace imunoise::io
