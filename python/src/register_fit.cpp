// imunoise.fit: the noise-model fit of a NumPy record, returned as the same document as
// `imunoise fit --format json` (a dict), built by the library's fit report.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/series.hpp"
#include "imunoise/spec/comparison.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/units.hpp"
#include "imunoise/io/timestamps.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "preprocessing.hpp"
#include "imunoise/load/load.hpp"
#include "to_python.hpp"

#include "array_view.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The rate unit the report speaks in, from the user's unit of the samples.
fit::RecordInfo describe(InputKind kind, const std::string& units, double rate_hz,
                         std::size_t n_samples) {
  fit::RecordInfo info;
  info.source = "array";
  info.rate_hz = rate_hz;
  info.n_samples = n_samples;
  if (units.empty()) {
    info.unit_label = "input unit";
    return info;
  }
  const Unit given = parse_unit(units);
  info.rate_unit = kind == InputKind::angle ? derivative_unit(given) : given;
  if (kind == InputKind::rate) integral_unit(info.rate_unit);  // throws unless a rate
  info.unit_label = info.rate_unit.name;
  info.gyro = info.rate_unit.quantity == Quantity::angular_rate;
  return info;
}

py::object fit_array(const Array& data, double rate, const std::string& data_type,
                     const std::string& units, const std::string& method,
                     const std::string& terms, double level, const std::string& taus,
                     const std::string& selection, bool gls, int min_dominant_taus,
                     const std::string& spec_name, double tau_min, double tau_max,
                     bool keep_short_taus, bool exact_model, bool auto_terms, int bootstrap,
                     std::uint64_t seed, bool robust, const PreprocessArgs& preprocessing) {
  if (data.ndim() != 1) throw InputError("data must be a 1-D array, got " + std::to_string(data.ndim()) + "-D");
  checked_rate_hz(rate);
  const std::span<const double> samples(data.data(), static_cast<std::size_t>(data.shape(0)));
  fit::FitOptions options;
  options.method = fit::parse_method(method);
  options.level = level;
  options.selection = fit::parse_selection(selection);
  options.use_correlation = gls;
  options.min_dominant_taus = min_dominant_taus;
  if (options.method == fit::Method::gmwm) {
    options.gmwm.bootstrap = bootstrap;
    options.gmwm.seed = seed;
    options.gmwm.robust = robust;
  } else if (bootstrap != 0) {
    throw InputError("bootstrap needs method='gmwm'");
  } else if (robust) {
    throw InputError("robust=True needs method='gmwm' (the robust GMWM); fix: method='gmwm', or drop robust");
  }
  fit::parse_method_terms(terms, options);  // gmwm: "N,K,GM,GM" or "auto" (the default list)
  options.tau_min_s = tau_min;
  options.tau_max_s = tau_max;
  options.exclude_distorted = !keep_short_taus;
  options.model_mismatch = !exact_model;
  options.auto_extra_terms = auto_terms;
  std::string why;
  if (!options.IsValid(&why)) throw InputError("fit options: " + why);
  const InputKind kind = parse_input_kind(data_type);
  const fit::RecordInfo info = describe(kind, units, rate, samples.size());
  const TauGrid grid = parse_tau_grid(taus);
  if (!spec_name.empty() && units.empty()) {
    throw InputError("spec comparison needs the unit of the data: pass units='deg/s' (or the "
                     "sensor's unit)");
  }
  const std::optional<Spec> spec =
      spec_name.empty() ? std::nullopt : std::optional<Spec>(resolve_spec(spec_name));

  fit::FitResult result;
  if (preprocessing.any()) {
    // Timestamps or preprocessing: the record built as the command line builds it,
    // fitted by the study's fit stage (a split record is fitted to its pooled curve).
    if (kind != InputKind::rate) {
      throw InputError("skip, detrend, outliers, gaps, davar, temperature and time work on rate samples; "
                       "fix: pass data_type='rate'");
    }
    nlohmann::json report;
    PreparedRecord prepared = prepare_record(samples, py::float_(rate), units, preprocessing, options);
    {
      py::gil_scoped_release release;
      result = study::fit_channel(prepared.record, options, grid);
      report = fit::report_json(study::record_info(prepared.record), options, result);
      study::add_provenance(prepared.record, options, report);
    }
    report["spec_comparison"] =
        spec ? comparison_json(compare(result.coefficients, *spec)) : nlohmann::json(nullptr);
    return to_python(report);
  }
  {
    py::gil_scoped_release release;
    if (const std::size_t i = first_non_finite(samples); i < samples.size()) {
      throw InputError("sample " + std::to_string(i) + " is not finite; remove or repair it");
    }
    // The record as the loader makes it (SI; a rate integrated from its offset), fitted by the
    // one Record fit. An angle unit and its rate (deg, deg/s) share to_si, the seconds being SI.
    Record record;
    record.name = record.source = "array";
    record.kind = kind;
    record.rate_hz = rate;
    record.rate_unit = info.rate_unit;
    record.unit_given = !units.empty();
    std::vector<double> values(samples.begin(), samples.end());
    if (const double to_si = info.rate_unit.to_si; to_si != 1.0) {
      for (double& v : values) v *= to_si;
    }
    record = load::finish_rates(std::move(record), std::move(values), {});
    result = study::fit_channel(record, options, grid);
  }
  nlohmann::json report = fit::report_json(info, options, result);
  report["spec_comparison"] =
      spec ? comparison_json(compare(result.coefficients, *spec)) : nlohmann::json(nullptr);
  return to_python(report);
}

}  // namespace

void register_fit(py::module_& m) {
  m.def("fit", [](const Array& data, const py::object& rate, const std::string& data_type, const std::string& units,
                  const std::string& method, const std::string& terms, double level, const std::string& taus,
                  const std::string& selection, bool gls, int min_dominant_taus, const std::string& spec_name,
                  double tau_min, double tau_max, bool keep_short_taus, bool exact_model, bool auto_terms,
                  int bootstrap, std::uint64_t seed, bool robust, const py::object& time, const py::object& skip, const std::string& detrend,
                  const py::object& outliers, const std::string& gaps, bool davar, double davar_window,
                  const py::object& temperature, double temperature_bin) {
          // Preprocessing keywords (preprocessing.hpp); rate may come from time= instead.
          const PreprocessArgs pre{time, skip, detrend, outliers, gaps, davar, davar_window, temperature, temperature_bin};
          double rate_hz = rate.is_none() ? 0.0 : rate.cast<double>();
          if (rate.is_none() && !time.is_none()) {
            const Array t = Array::ensure(time);
            if (!t || t.ndim() != 1) throw InputError("time must be a 1-D array of timestamps (s)");
            rate_hz = io::analyze_timing({t.data(), static_cast<std::size_t>(t.shape(0))}, "array").rate_hz;
          }
          return fit_array(data, rate_hz, data_type, units, method, terms, level, taus, selection, gls,
                           min_dominant_taus, spec_name, tau_min, tau_max, keep_short_taus, exact_model,
                           auto_terms, bootstrap, seed, robust, pre);
        },
        py::arg("data"), py::arg("rate") = py::none(), py::arg("data_type") = "rate",
        py::arg("units") = "", py::arg("method") = "wls", py::arg("terms") = "Q,N,B,K",
        py::arg("level") = 0.95, py::arg("taus") = "octave", py::arg("selection") = "none",
        py::arg("gls") = false, py::arg("min_dominant_taus") = 2, py::arg("spec") = "",
        py::arg("tau_min") = 0.0, py::arg("tau_max") = 0.0, py::arg("keep_short_taus") = false,
        py::arg("exact_model") = false, py::arg("auto_terms") = true, py::arg("bootstrap") = 0,
        py::arg("seed") = 1, py::arg("robust") = false,
        py::arg("time") = py::none(), py::arg("skip") = py::none(), py::arg("detrend") = "none",
        py::arg("outliers") = py::none(), py::arg("gaps") = "fail", py::arg("davar") = false,
        py::arg("davar_window") = 0.0, py::arg("temperature") = py::none(), py::arg("temperature_bin") = 5.0,
        "Noise-model coefficients (Q, N, B, K, R; terms may add GM and SIN, the optional "
        "Gauss-Markov and sinusoid terms) of a record with 95% intervals and verdicts; "
        "returns the dict of `imunoise fit --format json` (data_type 'rate' by default; "
        "spec='tg100' or a YAML spec file adds the datasheet comparison). As the command "
        "line's switches: tau_min / tau_max (s, 0: no limit) restrict the fitted taus "
        "(--tau-min/--tau-max); keep_short_taus keeps the shortest taus bent by the sampling "
        "chain (--keep-short-taus); exact_model drops the model-mismatch scatter "
        "(--exact-model); auto_terms=False does not try GM and SIN automatically when chi2 "
        "rejects the power-law model (--no-auto-terms). method='gmwm' fits by the generalized "
        "method of wavelet moments: terms like 'N,K,GM,GM' (GM repeated) or 'auto' (WVIC "
        "selection; the default terms mean auto), bootstrap=R parametric-bootstrap replicates "
        "and seed= (--bootstrap, --seed), robust=True the robust GMWM for records with outliers "
        "(--robust), the term BGM flicker as Gauss-Markov states; the result then has a 'gmwm' section (terms with "
        "intervals, candidates, J test, WVIC) and terms['GM'] lists every Gauss-Markov term. "
        "Preprocessing keywords as imunoise.dev: "
        "time=, skip=, detrend=, outliers=, gaps=, davar=, davar_window=, temperature=, "
        "temperature_bin= (a fit per temperature bin under \"temperature_bins\").");
}

}  // namespace imunoise::python
