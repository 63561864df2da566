#include "text.hpp"

#include <cmath>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/spec/exports.hpp"

namespace imunoise::exports::detail {

std::string number(double value) { return round_trip_number(value); }

bool present(const Coefficient& c) { return c.identified && std::isfinite(c.value) && c.value > 0.0; }

namespace {

std::string term_line(std::string_view comment, std::string_view symbol, const Coefficient& c,
                      std::string_view unit, double level) {
  if (!present(c)) {
    return fmt::format("{}   {} not identified{}\n", comment, symbol,
                       c.note.empty() ? std::string() : " (" + c.note + ")");
  }
  std::string interval = "no interval";
  if (std::isfinite(c.ci_low) && std::isfinite(c.ci_high)) {
    interval = fmt::format("{:.0f}% interval {:.6g} .. {:.6g}", level * 100.0, c.ci_low, c.ci_high);
  }
  return fmt::format("{}   {} = {:.6g} {} ({})\n", comment, symbol, c.value, unit, interval);
}

std::string sensor_lines(std::string_view comment, const std::optional<SensorModel>& s, bool gyro) {
  const char* what = gyro ? "gyroscope" : "accelerometer";
  if (!s) {
    return fmt::format("{} {}: NOT MEASURED (no {} channel): its values are placeholders\n", comment,
                       what, what);
  }
  const auto& c = s->coefficients;
  std::string out = fmt::format("{} {}: channels {} ({})\n", comment, what, s->channels, s->selection);
  out += term_line(comment, "N (white noise)", c.random_walk, gyro ? "rad/s/sqrt(Hz)" : "m/s^2/sqrt(Hz)",
                   c.confidence_level);
  out += term_line(comment, "K (bias random walk)", c.rate_random_walk,
                   gyro ? "rad/s^2/sqrt(Hz)" : "m/s^3/sqrt(Hz)", c.confidence_level);
  out += term_line(comment, "B (bias instability)", c.bias_instability, gyro ? "rad/s" : "m/s^2",
                   c.confidence_level);
  return out;
}

}  // namespace

std::string measured_header(const ExportModel& model, std::string_view target_title,
                            std::string_view comment) {
  std::string out;
  out += fmt::format("{} {} written by imunoise 0.1.0 from an Allan-variance fit (IEEE Std 952).\n",
                     comment, target_title);
  out += fmt::format("{} measured: {} at {} Hz\n", comment,
                     model.source.empty() ? std::string("(recording not named)") : model.source,
                     number(model.rate_hz));
  out += sensor_lines(comment, model.gyro, true);
  out += sensor_lines(comment, model.accel, false);
  for (const auto& line : not_carried(model, target_title)) out += fmt::format("{} {}\n", comment, line);
  const double f = model.inflation;
  out += fmt::format("{} inflation factor: {}{}\n", comment, number(f),
                     f == 1.0 ? " (values are the measured ones)"
                              : " (every noise value below = measured x " + number(f) +
                                    "; a variance = measured x " + number(f * f) + ")");
  return out;
}

Value scaled(const std::optional<SensorModel>& sensor, Coefficient NoiseCoefficients::*term,
             double factor, double inflation, std::string_view symbol) {
  if (!sensor) return {std::nullopt, "sensor not measured"};
  const Coefficient& c = sensor->coefficients.*term;
  if (!present(c)) {
    return {std::nullopt, fmt::format("{} not identified{}", symbol, c.note.empty() ? "" : " (" + c.note + ")")};
  }
  Value v{c.value * factor * inflation, ""};
  if (std::isfinite(c.ci_low) && std::isfinite(c.ci_high)) {
    v.low = c.ci_low * factor * inflation;
    v.high = c.ci_high * factor * inflation;
    v.level = sensor->coefficients.confidence_level;
  }
  return v;
}

std::string interval_text(const Value& v) {
  if (!(std::isfinite(v.low) && std::isfinite(v.high))) return " (no interval)";
  return fmt::format(" ({:.0f}% interval {:.6g} .. {:.6g})", v.level * 100.0, v.low, v.high);
}

Value squared(Value v) {
  if (v.value) v.value = *v.value * *v.value;
  v.low *= v.low;
  v.high *= v.high;
  return v;
}

std::string key_line(std::string_view indent, std::string_view key, const Value& v,
                     std::string_view note, std::string_view consequence, std::string_view comment,
                     std::string_view separator, std::string_view terminator) {
  if (v.value) {
    return fmt::format("{}{}{}{}{}  {} {}{}\n", indent, key, separator, number(*v.value), terminator,
                       comment, note, interval_text(v));
  }
  return fmt::format("{}{} {}{}<FILL IN>{}  {} {} -- NOT MEASURED by imunoise: {}; {}\n", indent,
                     comment, key, separator, terminator, comment, note, v.why_absent, consequence);
}

void require_gyro(const ExportModel& model, std::string_view target) {
  if (!model.gyro) {
    throw InputError(fmt::format(
        "--export {}: no gyroscope channel was measured and {} needs the gyro values first; fix: "
        "fit a gyro channel (or analyze the record's gyro and accelerometer columns together)",
        target, target));
  }
}

}  // namespace imunoise::exports::detail
