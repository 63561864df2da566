#pragma once
// Temperature dependence: the samples are binned by a temperature channel into ranges of fixed
// width, and each bin gets its own coefficients from its own samples. A bin's samples are
// usually several runs (the temperature passes through the range more than once); each run is
// a segment and the overlapping Allan sums are pooled over them (preprocess.hpp), never joined.
//
// Per bin: the bias (mean rate), the angle/velocity random walk read off the overlapping Allan
// deviation at the tau nearest 1 s, N = sigma(tau) sqrt(tau) (exact for white rate noise), and
// the bias-instability floor B = min sigma / 0.664 (IEEE 952 flicker read-off); and the full
// noise-model fit (fit::fit_allan: Q N B K R with intervals and the fit's diagnostics) of the
// bin's pooled curve, with the estimate covariance of one record of the bin's summed length.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/deviation.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/report.hpp"

namespace imunoise::preprocess {

struct TemperatureBin {
  double low = 0.0;             ///< bin range [low, high) in the temperature channel's unit
  double high = 0.0;
  std::size_t samples = 0;
  std::size_t segments = 0;     ///< contiguous runs of samples in the bin
  double mean_temperature = 0.0;
  double bias_si = 0.0;         ///< mean rate (SI)
  double bias_stderr_si = 0.0;  ///< sample sd / sqrt(samples): white-noise standard error (SI)
  double random_walk_si = 0.0;  ///< N = sigma(tau) sqrt(tau) at the tau nearest 1 s (SI * sqrt(s)); NaN if none
  double random_walk_tau_s = 0.0;
  double bias_instability_si = 0.0;  ///< min sigma / 0.664 (SI); NaN if no tau
  std::vector<DevPoint> oadev;  ///< pooled over the bin's segments (SI)
  /// The noise-model fit of `oadev`; empty when no fit was asked for or it failed (fit_error).
  std::optional<fit::FitResult> fit;
  std::string fit_error;        ///< why the bin's curve could not be fitted ("" when fitted)
};

/// Bins rate samples (SI, at rate_hz) by temperature into [k w, (k+1) w) ranges of width
/// `bin_width`; bins with fewer than `min_samples` samples are left out. Throws InputError for
/// a non-positive width, mismatched lengths or a non-finite temperature. With `fit_options`,
/// each bin's pooled oadev is also fitted (a bin whose curve cannot be fitted gets fit_error,
/// the others are still fitted). `breaks`: samples that start a new run even in the same bin
/// (the first sample after each timestamp gap of a record split at its gaps).
std::vector<TemperatureBin> temperature_bins(std::span<const double> rate_si, std::span<const double> temperature,
                                             double rate_hz, double bin_width, std::size_t min_samples = 1000,
                                             const fit::FitOptions* fit_options = nullptr,
                                             std::span<const std::size_t> breaks = {});

/// The bins as a JSON array: range, samples, runs, mean temperature, bias with its standard
/// error, the N and B read-offs (SI; null when absent) and, when fitted, "fit": the fit's
/// document (fit::report_json, source "<record.source> temperature [low, high)") or
/// "fit_error". `record` gives the rate unit and labels; its n_samples is replaced per bin.
nlohmann::json temperature_bins_json(const std::vector<TemperatureBin>& bins, const fit::RecordInfo& record,
                                     const fit::FitOptions& options);

/// One line per bin for text tables: range, samples, bias, and the fitted Q N B K (value
/// [ci_low, ci_high] in the record's unit label, "-" for terms not identified) or the fit error.
std::vector<std::string> temperature_bins_lines(const std::vector<TemperatureBin>& bins,
                                                const fit::RecordInfo& record);

}  // namespace imunoise::preprocess
