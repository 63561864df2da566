#pragma once
// The preprocessing steps of a real record, in order, each saying what it removed: warm-up
// skip (fixed, or suggested by the dynamic Allan variance), temperature binning (on the rates
// as recorded after the skip), detrend, spikes, the split into segments at timestamp gaps and
// rejected spikes, and the dynamic Allan variance. The command line (--skip, --detrend,
// --outliers, --gaps, --davar, --temperature) and Python (skip=, detrend=, ...) both run this.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/fit/fit.hpp"
#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/preprocess/temperature.hpp"

namespace imunoise::preprocess {

struct PipelineOptions {
  std::string skip;              ///< "" (none), a duration ("30", "30s", "5min", "0.5h") or "auto"
  std::string detrend = "none";  ///< none | linear | quadratic
  std::string outliers;          ///< "" (not checked) | fail | report | reject
  bool split_gaps = false;       ///< split at the gap breaks given to run_pipeline
  bool davar = false;            ///< dynamic Allan variance and stationarity verdict
  double davar_window_s = 0.0;   ///< 0: record / 20 (at least 100 samples)
  std::string temperature;       ///< name of the temperature channel ("" : none), for messages
  double temperature_bin = 5.0;  ///< bin width, in the temperature channel's unit
  /// Options of the per-bin fit (temperature_bins); the defaults when not given.
  std::optional<fit::FitOptions> temperature_fit;
};

/// True when any step is asked for.
bool wants_preprocessing(const PipelineOptions& options);

/// "30", "30s", "5min", "1.5h" -> seconds; InputError naming --skip otherwise.
double parse_duration_s(std::string_view text);

struct PipelineResult {
  std::vector<double> values;     ///< rates after skip and detrend (SI); rejected spikes still in
  std::vector<Segment> segments;  ///< ranges of `values` analysed separately; empty: one record
  std::size_t skipped = 0;        ///< samples removed at the start
  std::vector<std::string> notes; ///< one line per step: what was removed and how much
  std::optional<DavarResult> davar;
  std::vector<TemperatureBin> temperature_bins;
};

/// Runs the steps on rate samples (SI) at rate_hz. `gap_breaks`: index of the first sample
/// after each timestamp gap (used with split_gaps). `temperature`: one value per sample (empty
/// when no temperature channel). `source` names the record in messages; `unit` labels SI values
/// ("rad/s", "m/s^2" or "input unit"). Throws InputError naming the record and the fix (a skip
/// longer than the record, unknown option values, --outliers fail with spikes, a temperature
/// channel of another length).
PipelineResult run_pipeline(const PipelineOptions& options, std::vector<double> values, double rate_hz,
                            std::span<const std::size_t> gap_breaks, std::vector<double> temperature,
                            std::string_view source, std::string_view unit);

/// The dynamic Allan variance as the "davar" object of `imunoise dev --format json`: window,
/// step, window starts, taus, the variance per window and tau (SI), the reference, the flags,
/// the verdict, the change times and the suggested skip.
nlohmann::json davar_json(const DavarResult& davar);

}  // namespace imunoise::preprocess
