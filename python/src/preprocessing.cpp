// The preprocessing keyword arguments of imunoise.dev / imunoise.fit: parsed here, run by the
// library's pipeline (imunoise/preprocess/pipeline.hpp), the record built as the command line
// builds it (imunoise/load/load.hpp: finish_rates).
#include "preprocessing.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/io/timestamps.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/units.hpp"

#include "array_view.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> vector_of(const py::object& value, const char* what, std::size_t expected) {
  const Array a = Array::ensure(value);
  if (!a || a.ndim() != 1) throw InputError(std::string(what) + " must be a 1-D array of numbers");
  std::vector<double> out(a.data(), a.data() + a.shape(0));
  if (out.size() != expected) {
    throw InputError(std::string(what) + " has " + std::to_string(out.size()) + " values but the data " +
                     std::to_string(expected) + "; fix: give one per sample");
  }
  return out;
}

std::string skip_text(const py::object& skip) {
  if (skip.is_none()) return "";
  if (py::isinstance<py::str>(skip)) return skip.cast<std::string>();
  // 17 significant digits: the duration parser reads back the very double given.
  return fmt::format("{:.17g}", skip.cast<double>());
}

}  // namespace

Unit rate_unit_of(const std::string& units) {
  if (units.empty()) return Unit{"input unit", Quantity::dimensionless, 1.0};
  Unit unit = parse_unit(units);
  if (unit.quantity == Quantity::angle || unit.quantity == Quantity::time) {
    throw InputError("units='" + units + "' is an angle or time unit but the samples are rates; "
                     "give a rate unit such as 'deg/s', 'rad/s' or 'm/s^2'");
  }
  return unit;
}

void scale_to_si(std::vector<double>& values, const Unit& unit) {
  if (unit.to_si == 1.0) return;
  for (double& v : values) v *= unit.to_si;
}

bool PreprocessArgs::any() const {
  return !time.is_none() || !skip.is_none() || detrend != "none" || !outliers.is_none() || gaps != "fail" ||
         davar || !temperature.is_none();
}

PreparedRecord prepare_record(std::span<const double> samples, const py::object& rate_arg, const std::string& units,
                              const PreprocessArgs& args, const std::optional<fit::FitOptions>& temperature_fit) {
  if (args.gaps != "fail" && args.gaps != "split" && args.gaps != "allow") {
    throw InputError("gaps='" + args.gaps + "' is not known; fix: pass 'fail', 'split' or 'allow'");
  }
  PreparedRecord out;
  study::Record& r = out.record;
  r.name = "array";
  r.source = "array";
  r.kind = InputKind::rate;
  std::vector<double> values(samples.begin(), samples.end());
  if (values.empty()) throw InputError("array: no samples");
  if (const std::size_t i = first_non_finite(values); i < values.size()) {
    throw InputError("array: sample " + std::to_string(i) + " is not finite (NaN or inf); remove or repair it");
  }
  double rate = rate_arg.is_none() ? 0.0 : rate_arg.cast<double>();
  std::vector<std::size_t> breaks;
  if (!args.time.is_none()) {
    const auto time_s = vector_of(args.time, "time", values.size());
    r.timing = io::check_timing(time_s, "array", nullptr, args.gaps != "fail");
    if (rate > 0.0 && std::abs(r.timing->rate_hz / rate - 1.0) > 0.01) {
      throw InputError("array: rate " + fmt::format("{:g}", rate) + " Hz disagrees with the timestamps (" +
                       fmt::format("{:.6g}", r.timing->rate_hz) + " Hz from the median interval); fix: drop rate");
    }
    if (!(rate > 0.0)) rate = r.timing->rate_hz;
    if (args.gaps == "split") {
      for (const auto& g : r.timing->gaps) breaks.push_back(g.index);
    }
  } else if (args.gaps == "split") {
    throw InputError("gaps='split' needs the timestamps: pass time=recording.time_s (seconds, one per sample)");
  }
  checked_rate_hz(rate, "time=");
  r.rate_hz = rate;
  r.unit_given = !units.empty();
  r.rate_unit = rate_unit_of(units);
  scale_to_si(values, r.rate_unit);
  preprocess::PipelineOptions options;
  options.skip = skip_text(args.skip);
  options.detrend = args.detrend;
  options.outliers = args.outliers.is_none() ? std::string() : args.outliers.cast<std::string>();
  options.split_gaps = args.gaps == "split";
  options.davar = args.davar;
  options.davar_window_s = args.davar_window_s;
  options.temperature_bin = args.temperature_bin;
  options.temperature_fit = temperature_fit;
  std::vector<double> temperature;
  if (!args.temperature.is_none()) {
    options.temperature = "temperature";
    temperature = vector_of(args.temperature, "temperature", values.size());
  }
  py::gil_scoped_release release;  // the arguments are read: the rest is the library's work
  // The loader's road from SI rates to a record: preprocessing, segments, integration.
  out.record = load::finish_rates(std::move(r), std::move(values), options, breaks, std::move(temperature));
  return out;
}

}  // namespace imunoise::python
