// Compiled building blocks of the AllanTools compatibility layer (python/imunoise/allantools.py):
// the estimators at explicit averaging factors, with AllanTools' ranges where they differ from
// Stable32's, and the EDF, interval and autocorrelation functions of the confidence module.
// The tau-list conventions and the result shapes are Python's business; the arithmetic is here.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/confidence/noise_id.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/total.hpp"

#include "array_view.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

// (devs, ns) of `name` on phase samples at each averaging factor, both float64 arrays as
// AllanTools returns them. totdev runs over its whole reflected range m <= N-1 (AllanTools);
// every other estimator over its usual domain, which contains every m that AllanTools keeps
// (n >= 2). A non-finite sample is an error naming it, never a NaN result.
py::tuple deviation_at_factors(const std::string& name, const Array& phase_array, double rate,
                               const std::vector<std::size_t>& factors, unsigned threads) {
  const Estimator estimator = parse_estimator(name);
  checked_rate_hz(rate);
  const auto phase = view(phase_array);
  std::vector<DevPoint> points;
  {
    py::gil_scoped_release release;
    if (const std::size_t i = first_non_finite(phase, threads); i < phase.size()) {
      throw InputError("sample " + std::to_string(i) + " is not finite; remove or repair it");
    }
    points = estimator == Estimator::totdev
                 ? totdev_reflected_range(phase, 1.0 / rate, factors, {threads})
                 : compute_deviation(estimator, phase, 1.0 / rate, factors, {threads});
  }
  const auto n = static_cast<py::ssize_t>(points.size());
  py::array_t<double> devs(n), ns(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& p = points[static_cast<std::size_t>(i)];
    if (!std::isfinite(p.dev)) {
      throw InputError("the values are too large: their differences overflow; rescale the data");
    }
    devs.mutable_at(i) = p.dev;
    ns.mutable_at(i) = static_cast<double>(p.n);
  }
  return py::make_tuple(devs, ns);
}

// AllanTools' frequency-to-phase integration: x[0] = 0, x[k] = sum_{i<k} (y[i] - mean) / rate,
// compensated (phase.hpp).
py::array_t<double> integrate_frequency(const Array& freq, double rate) {
  checked_rate_hz(rate);
  const auto y = view(freq);
  std::vector<double> x;
  {
    py::gil_scoped_release release;
    x = phase_from_rate(y, 1.0 / rate, compensated_mean(y));
  }
  py::array_t<double> out(static_cast<py::ssize_t>(x.size()));
  std::copy(x.begin(), x.end(), out.mutable_data());
  return out;
}

double greenhall_edf(int alpha, int d, std::size_t m, std::size_t n_phase, bool overlapping,
                     bool modified) {
  if (d < 1 || d > 3) throw InputError("d must be 1, 2 or 3, got " + std::to_string(d));
  if (alpha < kMinNoiseAlpha || alpha > kMaxNoiseAlpha) {
    throw InputError("alpha must be an integer in -4..2, got " + std::to_string(alpha));
  }
  if (alpha + 2 * d <= 1) {
    throw InputError("alpha + 2 d must exceed 1 (the variance diverges), got alpha = " +
                     std::to_string(alpha) + ", d = " + std::to_string(d));
  }
  return greenhall_riley_edf(alpha, DifferenceVariance{d, modified, overlapping}, m, n_phase);
}

double sp1065_total_edf(const std::string& name, int alpha, std::size_t m, std::size_t n_phase) {
  return total_edf(parse_estimator(name), alpha, m, n_phase).value;
}

py::tuple interval(double dev, double edf, double level) {
  const ConfidenceInterval ci = chi2_interval(dev, edf, level);
  return py::make_tuple(ci.low, ci.high);
}

double lag1_acf(const Array& values) { return lag1_autocorrelation(view(values)); }

}  // namespace

void register_allantools(py::module_& m) {
  m.def("_at_deviation", &deviation_at_factors, py::arg("estimator"), py::arg("phase"),
        py::arg("rate"), py::arg("factors"), py::arg("threads") = 0u,
        "(devs, ns) at explicit averaging factors, float64 (AllanTools layer).");
  m.def("_at_frequency2phase", &integrate_frequency, py::arg("freq"), py::arg("rate"),
        "x[0] = 0, x[k] = sum_{i<k} (y[i] - mean(y)) / rate (compensated).");
  m.def("_greenhall_edf", &greenhall_edf, py::arg("alpha"), py::arg("d"), py::arg("m"),
        py::arg("n_phase"), py::arg("overlapping"), py::arg("modified"),
        "Greenhall & Riley EDF (NaN when the data are too short).");
  m.def("_total_edf", &sp1065_total_edf, py::arg("estimator"), py::arg("alpha"), py::arg("m"),
        py::arg("n_phase"), "NIST SP 1065 EDF of the total family and Theo1 (NaN outside).");
  m.def("_chi2_interval", &interval, py::arg("dev"), py::arg("edf"), py::arg("level"),
        "(low, high) chi-squared bounds of a deviation.");
  m.def("_lag1_autocorrelation", &lag1_acf, py::arg("values"),
        "Lag-1 autocorrelation about the mean (NaN for < 3 values or zero variance).");
}

}  // namespace imunoise::python
