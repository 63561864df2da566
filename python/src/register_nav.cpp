// Navigation error growth from Python: the dict of `imunoise nav --format json`, with every
// per-time series of each model as a NumPy array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imunoise/error.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/units.hpp"
#include "to_python.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

nav::GyroAxisNoise from_fit_object(const py::handle& fit, const std::string& name) {
  const std::string text = py::module_::import("json").attr("dumps")(fit).cast<std::string>();
  return nav::axis_from_fit_json(nlohmann::json::parse(text), name);
}

py::object nav_call(double N, double B, double K, double Q, double R, double bias, double gm_sigma, double gm_tau,
                    const std::string& units, const py::object& fit, double hours, double latitude, double velocity,
                    double step, double dt, const py::object& model, std::size_t runs, std::uint64_t seed,
                    unsigned threads, std::optional<double> sigma_eps, bool earth_rate, bool signed_constants) {
  const Unit unit = parse_unit(units);
  if (unit.quantity != Quantity::angular_rate) {
    throw InputError("units='" + units + "' is not an angular rate: give gyro coefficients, e.g. units='deg/s'");
  }
  if (!(hours > 0.0) || !std::isfinite(hours)) throw InputError("hours must be positive");
  if (!(std::abs(latitude) <= 90.0)) throw InputError("latitude must lie within [-90, 90] deg");
  nav::NavOptions o;
  const bool coefficients = N != 0 || B != 0 || K != 0 || Q != 0 || R != 0 || gm_sigma != 0;
  if (!fit.is_none() && coefficients) throw InputError("give either coefficients or fit=..., not both");
  if (fit.is_none()) {
    const nav::GyroAxisNoise a = nav::axis_from_coefficients({Q, N, B, K, R, gm_sigma, gm_tau}, unit, {"", '_'});
    for (auto& x : o.axes) x = a;
  } else if (py::isinstance<py::dict>(fit)) {
    const nav::GyroAxisNoise a = from_fit_object(fit, "fit");
    for (auto& x : o.axes) x = a;
  } else {
    const auto list = fit.cast<std::vector<py::object>>();
    if (list.size() != 3) throw InputError("fit must be one fit dict or a list of three (x north, y east, z down)");
    for (std::size_t i = 0; i < 3; ++i) o.axes[i] = from_fit_object(list[i], "fit[" + std::to_string(i) + "]");
  }
  for (auto& x : o.axes) x.bias_rad_s = bias * unit.to_si;
  o.duration_s = hours * 3600.0;
  o.step_s = std::min(step, o.duration_s);
  o.dt_s = dt;
  o.latitude_rad = latitude * std::numbers::pi / 180.0;
  o.velocity_m_s = velocity;
  o.earth_rate = earth_rate;
  std::string models;
  if (py::isinstance<py::str>(model)) {
    models = model.cast<std::string>();
  } else {
    for (const auto& m : model.cast<std::vector<std::string>>()) models += (models.empty() ? "" : ",") + m;
  }
  o.models = nav::parse_models(models);
  o.runs = runs;
  o.seed = seed;
  o.signed_constants = signed_constants;
  o.threads = threads;
  if (sigma_eps) o.paper_sigma_eps_rad_s = *sigma_eps * unit.to_si;
  nav::NavResult result;
  {
    py::gil_scoped_release release;
    result = nav::navigation_error(o);
  }
  py::dict doc = to_python(nav::report_json(result));
  py::module_ np = py::module_::import("numpy");
  for (auto m : doc["models"]) {
    py::dict md = m.cast<py::dict>();
    for (auto item : md) {
      if (py::isinstance<py::list>(item.second)) md[item.first] = np.attr("asarray")(item.second, "float64");
    }
  }
  return std::move(doc);
}

}  // namespace

void register_nav(py::module_& m) {
  m.def("nav", &nav_call, py::kw_only(), py::arg("N") = 0.0, py::arg("B") = 0.0, py::arg("K") = 0.0,
        py::arg("Q") = 0.0, py::arg("R") = 0.0, py::arg("bias") = 0.0, py::arg("gm_sigma") = 0.0,
        py::arg("gm_tau") = 0.0, py::arg("units") = "deg/s", py::arg("fit") = py::none(), py::arg("hours") = 1.0,
        py::arg("latitude") = 58.5, py::arg("velocity") = 0.0, py::arg("step") = 60.0, py::arg("dt") = 1.0,
        py::arg("model") = "schuler,covariance", py::arg("runs") = 1000, py::arg("seed") = 1,
        py::arg("threads") = 0, py::arg("sigma_eps") = py::none(), py::arg("earth_rate") = true,
        py::arg("signed_constants") = false,
        "Navigation error growth (RMS latitude, longitude, path, radial vs time) from gyro noise given in `units` "
        "(N unit*sqrt(s), B unit, K unit/sqrt(s), Q unit*s, R unit/s, bias unit) or fit=imunoise.fit(...) dict "
        "(or a list of three: x north, y east, z down). model: 'paper', 'schuler', 'covariance', 'montecarlo' "
        "(comma string or list); signed_constants: the Monte Carlo takes bias and R as signed values, the same in "
        "every run (default: random constants per axis with that standard deviation, as the covariance). Returns the dict of `imunoise nav --format json`; each model's series "
        "(t_s, lat_deg, lon_deg, path_m, north_m, east_m, radial_m, ...) are NumPy arrays.");
}

}  // namespace imunoise::python
