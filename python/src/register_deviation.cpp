// Deviation estimators over NumPy arrays, without copying the input.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include <fmt/core.h>

#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/finite.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/series.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"

#include "array_view.hpp"
#include "imunoise/load/integrate.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

// Every phase sample enters some term of an overlapping difference of order r at factor m when
// N >= (r + 1) m (the index ranges [j m, j m + n - 1], j = 0..r, then join up), and a
// non-finite sample makes that term's square, and so the sum, non-finite. Finite results then
// vouch for the input, and the scan of it (a whole pass over memory) is not needed.
bool results_cover_input(Estimator estimator, std::size_t n_phase,
                         std::span<const std::size_t> factors) {
  const std::size_t order = estimator == Estimator::oadev ? 2 : estimator == Estimator::ohdev ? 3 : 0;
  if (order == 0) return false;
  return std::any_of(factors.begin(), factors.end(),
                     [&](std::size_t m) { return n_phase >= (order + 1) * m; });
}

// NaN/Inf input (or values whose integral overflows) is an error, never a NaN in the result.
void require_finite(std::span<const double> samples, Estimator estimator, std::size_t n_phase,
                    std::span<const std::size_t> factors, std::span<const DevPoint> points,
                    unsigned threads) {
  const bool all_finite = std::all_of(points.begin(), points.end(),
                                      [](const DevPoint& p) { return std::isfinite(p.dev); });
  if (all_finite && results_cover_input(estimator, n_phase, factors)) return;
  if (const std::size_t i = first_non_finite(samples, threads); i < samples.size()) {
    throw InputError("sample " + std::to_string(i) + " is not finite; remove or repair it");
  }
  if (!all_finite) {
    throw InputError("the values are too large: their differences overflow; rescale the data");
  }
}

// AllanTools-compatible: returns (taus, devs, errs, ns); errs = dev / sqrt(n) as AllanTools.
py::tuple deviation(const std::string& name, const Array& data, double rate,
                    const std::string& data_type, const py::object& taus, unsigned threads) {
  const Estimator estimator = parse_estimator(name);
  if (!(rate > 0)) throw InputError("rate must be positive (Hz), got " + fmt::format("{:g}", rate));
  const auto samples = view(data);
  const double tau0_s = 1.0 / rate;
  std::vector<double> integrated;
  std::span<const double> phase = samples;
  {
    py::gil_scoped_release release;
    if (parse_input_kind(data_type) == InputKind::rate) {
      integrated = load::integrate_rate(samples, rate);
      phase = integrated;
    }
  }
  TauGrid grid;
  if (py::isinstance<py::str>(taus)) {
    grid = parse_tau_grid(taus.cast<std::string>());
  } else if (!taus.is_none()) {
    grid.kind = TauGrid::Kind::taus_s;
    grid.taus_s = taus.cast<std::vector<double>>();
  }
  const auto factors = estimator_averaging_factors(estimator, grid, rate, phase.size());
  std::vector<DevPoint> points;
  {
    py::gil_scoped_release release;
    points = compute_deviation(estimator, phase, tau0_s, factors, {threads});
  }
  require_finite(samples, estimator, phase.size(), factors, points, threads);
  const auto n = static_cast<py::ssize_t>(points.size());
  py::array_t<double> out_taus(n), out_devs(n), out_errs(n);
  py::array_t<long long> out_ns(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& p = points[static_cast<std::size_t>(i)];
    out_taus.mutable_at(i) = p.tau_s;
    out_devs.mutable_at(i) = p.dev;
    out_errs.mutable_at(i) = p.dev / std::sqrt(static_cast<double>(p.n));
    out_ns.mutable_at(i) = static_cast<long long>(p.n);
  }
  return py::make_tuple(out_taus, out_devs, out_errs, out_ns);
}

}  // namespace

void register_deviation(py::module_& m) {
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  m.def("deviation", &deviation, py::arg("estimator"), py::arg("data"), py::arg("rate") = 1.0,
        py::arg("data_type") = "phase", py::arg("taus") = py::none(), py::arg("threads") = 0u,
        "Deviation by estimator name; returns (taus, devs, errs, ns) like AllanTools.");
}

}  // namespace imunoise::python
