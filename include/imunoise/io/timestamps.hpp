#pragma once
// Timestamps: the sample rate they imply, how regular they are, and where samples are missing.
//
// imunoise analyses equally spaced samples and never interpolates. A time column is therefore
// only checked: the rate is 1 / (median interval), irregular intervals are measured (jitter),
// intervals longer than 1.5 median intervals are reported as gaps, and intervals <= 0 (samples
// out of order or duplicated) are reported so the caller can refuse the record.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace imunoise::io {

class LineMap;  // text_reader.hpp: maps a sample index to its line in a text file

/// A timestamp as written, split so that large epoch values keep full resolution:
/// value = whole + fraction, in the file's time unit. "1700000000.123456789" becomes
/// {1700000000, 0.123456789}, and a ROS-style integer nanosecond count such as
/// "1600000000123456789" becomes {1600000000123456789, 0} (a double alone would round it to a
/// multiple of 256 ns).
struct SplitTime {
  std::int64_t whole = 0;   ///< integer part (time unit of the file)
  double fraction = 0.0;    ///< remaining part, |fraction| < 1 when written in plain decimal
  bool integer = false;     ///< written as a plain integer (no '.', no exponent)
};

/// Parses one timestamp cell: [+-]digits[.digits] is split exactly; any other form that
/// fast_float accepts as a double (exponent, more than 18 integer digits, nan, inf) is kept as
/// {0, value, false}. Returns nullopt for text that is not a number. The caller checks
/// is_finite().
std::optional<SplitTime> parse_split_time(std::string_view text);

/// Whether the split time is a finite number.
bool is_finite(const SplitTime& time);

/// The auto-detection rule for a time column with no unit given: the values are integer
/// nanoseconds when every one is written as an integer and the first has a magnitude above
/// 1e15 (no plausible clock counts seconds that high: 1e15 s is 3e7 years, while epoch
/// nanoseconds are ~1.7e18). Anything else is seconds.
bool looks_like_nanoseconds(std::span<const SplitTime> times);

/// Seconds elapsed since the first timestamp: out[i] = (t[i] - t[0]) * unit_to_s. The integer
/// parts are subtracted exactly before converting to double, so epoch nanoseconds keep 1 ns
/// resolution for spans up to 2^53 ns (104 days). Empty in, empty out.
std::vector<double> relative_seconds(std::span<const SplitTime> times, double unit_to_s);

/// Same for integer nanosecond counts (e.g. ROS header stamps): (t_ns[i] - t_ns[0]) * 1e-9.
std::vector<double> relative_seconds_from_ns(std::span<const std::int64_t> times_ns);

/// An interval longer than 1.5 median intervals.
struct TimeGap {
  std::size_t index = 0;               ///< 0-based sample after the gap
  std::optional<std::size_t> line;     ///< 1-based line of that sample, when read from text
  double duration_s = 0.0;             ///< the interval time[index] - time[index - 1] (s)
  std::size_t missing_samples = 0;     ///< round(duration / median interval) - 1, >= 1
};

/// An interval <= 0: the sample is out of order (dt < 0) or duplicates the previous time.
struct TimeDisorder {
  std::size_t index = 0;               ///< 0-based sample whose time is not after its predecessor
  std::optional<std::size_t> line;     ///< 1-based line of that sample, when read from text
  double time_s = 0.0;                 ///< its time, relative to the first sample (s)
  double previous_time_s = 0.0;        ///< the predecessor's time, relative to the first sample (s)
};

/// What the timestamps say about a record.
struct TimingReport {
  std::size_t n_samples = 0;
  double rate_hz = 0.0;            ///< 1 / median_dt_s (Hz)
  double median_dt_s = 0.0;        ///< median of all intervals (s); > 0
  double duration_s = 0.0;         ///< last time - first time (s)
  /// Jitter of the regular intervals (0 < dt <= 1.5 median; gaps and disorder excluded),
  /// relative to the median interval (dimensionless): sample standard deviation of dt / median,
  /// and max |dt - median| / median. Both 0 when fewer than 2 (resp. 1) regular intervals.
  double jitter_rel_std = 0.0;
  double jitter_rel_max = 0.0;
  std::vector<TimeGap> gaps;       ///< every gap, in order
  std::size_t missing_samples = 0; ///< sum of gaps[i].missing_samples
  std::vector<TimeDisorder> disorder;  ///< every out-of-order or duplicate sample, in order
};

/// Analyses timestamps (seconds; any origin). Gaps and disorder are reported, not thrown: call
/// require_ordered and require_no_gaps, or check_timing which does both. `source` names the
/// file in messages; `lines` (optional) maps samples to text lines for the report.
/// Throws InputError when there are fewer than 2 samples, a time is NaN or infinite, or the
/// median interval is <= 0 (no positive rate can be derived).
TimingReport analyze_timing(std::span<const double> time_s, std::string_view source,
                            const LineMap* lines = nullptr);

/// Throws InputError naming the first out-of-order or duplicate sample (its line or index and
/// its time), the number of such samples, and the fix (sort the file, remove duplicates).
void require_ordered(const TimingReport& report, std::string_view source);

/// Throws InputError naming the first gap (line or sample, duration, missing samples), the
/// number of gaps, and the fix: split the record at the gap, or pass --allow-gaps to treat the
/// samples as equally spaced; imunoise never interpolates.
void require_no_gaps(const TimingReport& report, std::string_view source);

/// analyze_timing, then require_ordered, then (unless allow_gaps) require_no_gaps.
TimingReport check_timing(std::span<const double> time_s, std::string_view source,
                          const LineMap* lines = nullptr, bool allow_gaps = false);

}  // namespace imunoise::io
