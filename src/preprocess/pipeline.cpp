#include "imunoise/preprocess/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::preprocess {

bool wants_preprocessing(const PipelineOptions& options) {
  return !options.skip.empty() || options.detrend != "none" || !options.outliers.empty() || options.split_gaps ||
         options.davar || !options.temperature.empty();
}

double parse_duration_s(std::string_view text_view) {
  const std::string text(text_view);
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const std::string unit = used ? text.substr(used) : "";
  const double factor = unit.empty() || unit == "s" ? 1.0 : unit == "min" ? 60.0 : unit == "h" ? 3600.0 : 0.0;
  if (used == 0 || factor == 0.0 || !std::isfinite(value) || value < 0.0) {
    throw InputError("--skip " + text + " is not a duration; fix: pass seconds (30, 30s), minutes (5min), "
                     "hours (0.5h) or auto");
  }
  return value * factor;
}

namespace {

double default_window_s(std::size_t n, double rate) {
  return std::max(static_cast<double>(n) / rate / 20.0, 100.0 / rate);
}

}  // namespace

PipelineResult run_pipeline(const PipelineOptions& options, std::vector<double> values, double rate,
                            std::span<const std::size_t> gap_breaks, std::vector<double> temperature,
                            std::string_view source_view, std::string_view unit_view) {
  const std::string source(source_view);
  const std::string unit(unit_view);
  PipelineResult out;
  if (!options.outliers.empty() && options.outliers != "fail" && options.outliers != "report" &&
      options.outliers != "reject") {
    throw InputError("--outliers " + options.outliers + " is not known; fix: pass fail, report or reject");
  }
  const auto order = parse_detrend(options.detrend);
  std::size_t skip = 0;
  if (options.skip == "auto") {
    DavarOptions d;
    d.window_s = default_window_s(values.size(), rate);
    const auto result = dynamic_allan(values, rate, d);
    skip = static_cast<std::size_t>(std::llround(result.suggested_skip_s * rate));
    out.notes.push_back(fmt::format(
        "skip auto: the dynamic Allan variance (window {:.6g} s) {}; skipped the first {:.6g} s ({} samples)",
        result.window_s, result.suggested_skip_s > 0 ? "flags a warm-up" : "flags no warm-up",
        result.suggested_skip_s, skip));
  } else if (!options.skip.empty()) {
    const double skip_s = parse_duration_s(options.skip);
    skip = static_cast<std::size_t>(std::llround(skip_s * rate));
    out.notes.push_back(fmt::format("skip: removed the first {:.6g} s ({} samples)", skip_s, skip));
  }
  if (skip >= values.size()) {
    throw InputError(source + ": --skip removes all " + std::to_string(values.size()) +
                     " samples; fix: skip less than the record");
  }
  out.skipped = skip;
  values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(skip));
  if (!options.temperature.empty()) {
    // Binned on the rates as recorded (after the skip, before detrending: the bias per bin is
    // what a temperature calibration needs).
    if (temperature.size() != values.size() + skip) {
      throw InputError(source + ": --temperature " + options.temperature + " has " + std::to_string(temperature.size()) +
                       " samples, the rate " + std::to_string(values.size() + skip) +
                       "; fix: choose a temperature column of the same record");
    }
    temperature.erase(temperature.begin(), temperature.begin() + static_cast<std::ptrdiff_t>(skip));
    const fit::FitOptions fit_options = options.temperature_fit.value_or(fit::FitOptions{});
    // With split gaps a run also ends at each gap: no term of a bin's curve spans one.
    std::vector<std::size_t> cuts;
    if (options.split_gaps) {
      for (const auto b : gap_breaks) {
        if (b > skip) cuts.push_back(b - skip);
      }
    }
    out.temperature_bins =
        temperature_bins(values, temperature, rate, options.temperature_bin, 1000, &fit_options, cuts);
    fit::RecordInfo info;
    info.source = source;
    info.rate_hz = rate;
    info.unit_label = unit;  // values are SI: rate_unit keeps to_si = 1
    for (const auto& line : temperature_bins_lines(out.temperature_bins, info)) out.notes.push_back(line);
    if (out.temperature_bins.empty()) {
      out.notes.push_back("temperature: no bin holds 1000 samples; fix: widen --temperature-bin");
    }
  }
  std::vector<std::size_t> breaks;
  if (options.split_gaps) {
    for (const auto b : gap_breaks) {
      if (b > skip) breaks.push_back(b - skip);
    }
  }
  if (order != DetrendOrder::none) {
    const auto r = detrend(values, rate, order);
    std::string coefficients;
    const char* powers[] = {"", "/s", "/s^2"};
    for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
      coefficients += fmt::format("{}c{} = {:.6g} {}{}", k ? ", " : "", k, r.coefficients[k], unit, powers[k]);
    }
    out.notes.push_back(fmt::format(
        "detrend {}: removed {} (RMS {:.6g} {} about the mean); this also removes rate ramp R and "
        "biases rate random walk K low", options.detrend, coefficients, r.removed_rms, unit));
  }
  std::vector<std::size_t> removed;
  if (!options.outliers.empty()) {
    const auto r = find_spikes(values, 0.0, source);
    std::string first;
    for (std::size_t k = 0; k < std::min<std::size_t>(r.indices.size(), 5); ++k) {
      first += fmt::format("{}{} ({:.6g} {})", k ? ", " : "", r.indices[k] + skip, values[r.indices[k]], unit);
    }
    const std::string summary = fmt::format(
        "{} spikes beyond {:.3g} robust sigma (median {:.6g} {}, 1.4826 MAD = {:.6g} {}){}{}",
        r.indices.size(), r.threshold_sigmas, r.median, unit, r.robust_sigma, unit,
        r.indices.empty() ? "" : " at samples ", first + (r.indices.size() > 5 ? ", ..." : ""));
    if (options.outliers == "fail" && !r.indices.empty()) {
      throw InputError(source + ": " + summary + "; fix: remove them, or pass --outliers reject "
                       "(split at them) or --outliers report");
    }
    if (options.outliers == "reject") {
      removed = r.indices;
      out.notes.push_back("outliers reject: " + summary + "; removed, the record split at each");
    } else {
      out.notes.push_back("outliers " + options.outliers + ": " + summary);
    }
  }
  if (!breaks.empty() || !removed.empty()) {
    out.segments = split_segments(values.size(), breaks, removed);
    std::size_t kept = 0;
    for (const auto& seg : out.segments) kept += seg.size();
    if (!breaks.empty()) {
      out.notes.push_back(fmt::format(
          "gaps split: {} gaps; analysed as {} segments ({} samples) whose Allan sums are pooled, no term "
          "spanning a gap (nothing interpolated)", breaks.size(), out.segments.size(), kept));
    }
  }
  if (options.davar) {
    DavarOptions d;
    d.window_s = options.davar_window_s > 0 ? options.davar_window_s : default_window_s(values.size(), rate);
    out.davar = dynamic_allan(values, rate, d);
    const auto& r = *out.davar;
    std::string changes;
    for (const double t : r.change_times_s) changes += fmt::format("{}{:.6g}", changes.empty() ? "" : ", ", t);
    out.notes.push_back(fmt::format(
        "davar: {} windows of {:.6g} s every {:.6g} s at {} taus: {}{}{}", r.avar.size(), r.window_s, r.step_s,
        r.tau_s.size(), r.stationary ? "stationary (no window outside its chi-squared band)" : "NOT stationary",
        changes.empty() ? "" : "; changes near t = " + changes + " s",
        r.suggested_skip_s > 0 ? fmt::format("; suggested --skip {:.6g}", r.suggested_skip_s) : ""));
  }
  out.values = std::move(values);
  return out;
}

nlohmann::json davar_json(const DavarResult& d) {
  return {{"window_s", d.window_s}, {"step_s", d.step_s}, {"window_start_s", d.window_start_s},
          {"tau_s", d.tau_s}, {"avar_si", d.avar}, {"reference_avar_si", d.reference_avar},
          {"window_flagged", d.window_flagged}, {"stationary", d.stationary},
          {"change_times_s", d.change_times_s}, {"suggested_skip_s", d.suggested_skip_s}};
}

}  // namespace imunoise::preprocess
