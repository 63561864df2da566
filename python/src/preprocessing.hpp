#pragma once
// The preprocessing keyword arguments shared by imunoise.dev and imunoise.fit (time=, skip=,
// detrend=, outliers=, gaps=, davar=, davar_window=, temperature=, temperature_bin=), and the
// record they turn rate samples into: the same steps and record as `--skip ... --temperature`
// on the command line (imunoise/preprocess/pipeline.hpp), only parsed here.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/fit/fit.hpp"
#include "imunoise/preprocess/pipeline.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/units.hpp"

namespace imunoise::python {

struct PreprocessArgs {
  pybind11::object time;         ///< None or timestamps (s), one per sample
  pybind11::object skip;         ///< None, seconds (number), "30s"/"5min"/"0.5h" or "auto"
  std::string detrend = "none";
  pybind11::object outliers;     ///< None, "fail", "report" or "reject"
  std::string gaps = "fail";     ///< "fail", "split" or "allow" (treat as equally spaced)
  bool davar = false;
  double davar_window_s = 0.0;
  pybind11::object temperature;  ///< None or one temperature per sample
  double temperature_bin = 5.0;
  /// True when any step, timestamps, or a gap policy other than 'fail' were given.
  [[nodiscard]] bool any() const;
};

/// A rate record after preprocessing (what the steps said is in the record's provenance).
struct PreparedRecord {
  study::Record record;
};

/// Rate samples (in `units`, "" : not given) at `rate` Hz (None: from `time`) through the
/// pipeline into a study record (SI, integrated; split records keep their segments and rates).
/// Raises InputError (ValueError) as the command line does. Call with the GIL held (it reads the
/// Python arguments, then releases it for the work).
PreparedRecord prepare_record(std::span<const double> samples, const pybind11::object& rate, const std::string& units,
                              const PreprocessArgs& args, const std::optional<fit::FitOptions>& temperature_fit);

/// The rate unit of `units` ("" : the unitless "input unit"); an angle or time unit is an
/// InputError, since the samples are rates.
Unit rate_unit_of(const std::string& units);

/// `values` (in `unit`) converted to SI in place.
void scale_to_si(std::vector<double>& values, const Unit& unit);

}  // namespace imunoise::python
