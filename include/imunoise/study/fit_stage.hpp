#pragma once
// The fit stage of the study: one record -> the noise model with its checks (constant or
// quantized records, saturation), and the fit's text table of `imunoise fit --format table`.
// The fit's JSON is fit::report_json (imunoise/fit/report.hpp), the datasheet comparison's
// comparison_json (imunoise/spec/report.hpp).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/deviation.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::study {

/// What the fit report says about the record.
fit::RecordInfo record_info(const Record& record);

/// The one fit of a record: oadev on `grid` (pooled over the segments of a split record), then
/// fit_curve. Every caller fits through here: the commands, the study, the fleet and Python.
/// In detail: oadev on `grid`, then fit::fit_allan, with the record's warnings first in
/// summary.warnings and the quantity (gyro or accelerometer) set from the unit. Throws
/// InputError naming the record when the rate is constant or no model can be fitted.
fit::FitResult fit_channel(const Record& record, const fit::FitOptions& options,
                           const TauGrid& grid = {});

/// The fit of an oadev curve already computed for `record` (its description: source, rate,
/// unit; the samples are not used), e.g. merged from the slices of `--mpi`, over `n_phase`
/// phase samples: fit::fit_allan with `warnings` first in summary.warnings and the quantity
/// set from the unit. InputError naming the record when no model can be fitted.
fit::FitResult fit_curve(const Record& record, std::span<const DevPoint> oadev_points, std::size_t n_phase,
                         const fit::FitOptions& options, const std::vector<std::string>& warnings = {});

/// Where the record came from and what preprocessing did, added to a document (each curve
/// object of `dev --format json`, the `fit` document, Python's dicts): "recording" {format,
/// stream, channel} when a file was read, "preprocessing" (one line per step), "davar", and
/// "temperature_bins" (each bin's fit with `bin_fit` options).
void add_provenance(const Record& record, const fit::FitOptions& bin_fit, nlohmann::json& document);

/// `imunoise fit --format table`: coefficients (record unit and customary), notes, eqs. 1-2,
/// summary, warnings and the residual per tau.
std::string fit_table(const Record& record, const fit::FitOptions& options,
                      const fit::FitResult& result);

/// The datasheet comparison (comparison_json) as a text table; "" for null.
std::string spec_table(const nlohmann::json& comparison);

}  // namespace imunoise::study
