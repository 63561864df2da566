#pragma once
// Shared pieces of the export texts (internal to src/export): the header saying what was
// measured, each value's interval and the inflation, and the number format.
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports::detail {

/// Shortest text that reads back to the same double, with a '.' (spec/exports.hpp).
std::string number(double value);

/// True when the term was identified with a positive value.
bool present(const Coefficient& c);

/// Comment lines (each starting with `comment` and a space) for the top of every file: the
/// tool, the recording, the rate, the channels of each sensor and how a triad's value was
/// chosen, the interval level, the inflation factor (always, 1 included), and a line per
/// measured term with its value and interval in SI.
std::string measured_header(const ExportModel& model, std::string_view target_title,
                            std::string_view comment);

/// One exported value: the measured term x `factor` x inflation, or why there is none.
struct Value {
  std::optional<double> value;
  std::string why_absent;  ///< "no accelerometer channel measured", "K not identified (...)"
  double low = std::numeric_limits<double>::quiet_NaN();   ///< the measured interval, same
  double high = std::numeric_limits<double>::quiet_NaN();  ///< scaling as the value
  double level = 0.0;                                      ///< its confidence level
};

/// " (95% interval lo .. hi)" in the value's scaling, or " (no interval)".
std::string interval_text(const Value& v);

/// The value and its interval squared (a variance from a standard deviation).
Value squared(Value v);

/// The term of a sensor (absent sensor or unidentified term: no value, with the reason).
Value scaled(const std::optional<SensorModel>& sensor, Coefficient NoiseCoefficients::*term,
             double factor, double inflation, std::string_view symbol);

/// "key: value  # note (95% interval lo .. hi)" or, without a value, "# key: <FILL IN>  # note -- NOT MEASURED: why;
/// consequence" so the consumer never reads a number imunoise did not measure.
std::string key_line(std::string_view indent, std::string_view key, const Value& v,
                     std::string_view note, std::string_view consequence,
                     std::string_view comment = "#", std::string_view separator = ": ",
                     std::string_view terminator = "");

/// Throws InputError "<target>: ..." unless a gyro model is present.
void require_gyro(const ExportModel& model, std::string_view target);

}  // namespace imunoise::exports::detail
