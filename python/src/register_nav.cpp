// Navigation error growth from Python: the dict of `imunoise nav --format json`, with every
// per-time series of each model as a NumPy array.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "imunoise/error.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/nav/request.hpp"
#include "imunoise/units.hpp"
#include "to_python.hpp"

namespace py = pybind11;

namespace imunoise::python {
namespace {

nav::GyroAxisNoise from_fit_object(const py::handle& fit, const std::string& name) {
  return nav::axis_from_fit_json(from_python(fit, name), name);
}

py::object nav_call(double N, double B, double K, double Q, double R, double bias, double gm_sigma, double gm_tau,
                    const std::string& units, const py::object& fit, double hours, double latitude, double velocity,
                    double step, double dt, const py::object& model, std::size_t runs, std::uint64_t seed,
                    unsigned threads, std::optional<double> sigma_eps, bool earth_rate, bool signed_constants,
                    double accel_N, double accel_B, double accel_K, double accel_Q, double accel_R, double accel_bias,
                    double accel_gm_sigma, double accel_gm_tau, const std::string& accel_units,
                    const std::vector<double>& outage, double initial_pos_m, double initial_vel_m_s,
                    double initial_att_deg, double align) {
  nav::NavRequest r;
  r.names = {"", '_'};
  r.fit_option = "fit=";
  r.per_axis_fit_option = "fit=[x, y, z]";
  r.coefficients = {Q, N, B, K, R, gm_sigma, gm_tau};
  r.coefficients_given = N != 0 || B != 0 || K != 0 || Q != 0 || R != 0 || gm_sigma != 0;
  if (py::isinstance<py::dict>(fit)) {
    const nav::ImuFits imu = nav::imu_from_document(from_python(fit, "fit"), "fit");
    r.fitted_axes = imu.gyro;
    r.fitted_accel_axes = imu.accel;
    r.measured_s = imu.measured_s;
  } else if (!fit.is_none()) {
    const auto list = fit.cast<std::vector<py::object>>();
    if (list.size() != 3) throw InputError("fit must be one fit dict or a list of three (x north, y east, z down)");
    for (std::size_t i = 0; i < 3; ++i) r.fitted_axes[i] = from_fit_object(list[i], fmt::format("fit[{}]", i));
  }
  r.accel_coefficients = {accel_Q, accel_N, accel_B, accel_K, accel_R, accel_gm_sigma, accel_gm_tau};
  r.accel_bias = accel_bias;
  r.accel_units = accel_units;
  r.bias = bias;
  r.units = units;
  r.hours = hours;
  r.outage_s = outage;
  r.initial_pos_m = initial_pos_m;
  r.initial_vel_m_s = initial_vel_m_s;
  r.initial_att_deg = initial_att_deg;
  r.align_s = align;
  r.latitude_deg = latitude;
  r.velocity_m_s = velocity;
  r.step_s = step;
  r.dt_s = dt;
  if (py::isinstance<py::str>(model)) {
    r.models = model.cast<std::string>();
  } else {
    r.models.clear();
    for (const auto& m : model.cast<std::vector<std::string>>()) r.models += (r.models.empty() ? "" : ",") + m;
  }
  r.runs = runs;
  r.seed = seed;
  r.threads = threads;
  r.sigma_eps = sigma_eps;
  r.earth_rate = earth_rate;
  r.signed_constants = signed_constants;
  const nav::NavOptions o = nav::plan_navigation(r);
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
        py::arg("signed_constants") = false, py::arg("accel_N") = 0.0, py::arg("accel_B") = 0.0,
        py::arg("accel_K") = 0.0, py::arg("accel_Q") = 0.0, py::arg("accel_R") = 0.0, py::arg("accel_bias") = 0.0,
        py::arg("accel_gm_sigma") = 0.0, py::arg("accel_gm_tau") = 0.0, py::arg("accel_units") = "m/s^2",
        py::arg("outage") = std::vector<double>{}, py::arg("initial_pos_m") = 0.0, py::arg("initial_vel_m_s") = 0.0,
        py::arg("initial_att_deg") = 0.0, py::arg("align") = 0.0,
        "Navigation error growth (RMS latitude, longitude, path, radial vs time) from gyro noise given in `units` "
        "(N unit*sqrt(s), B unit, K unit/sqrt(s), Q unit*s, R unit/s, bias unit) or fit=imunoise.fit(...) dict "
        "(or a list of three: x north, y east, z down), and accelerometer noise accel_N (velocity random walk), "
        "accel_B, accel_K, accel_Q, accel_R, accel_bias, accel_gm_sigma/accel_gm_tau in accel_units (m/s^2, g, mg, "
        "ug; N in accel_units*sqrt(s)), the same on every axis. outage=[10, 30, 60, 300] (s) adds the GNSS-outage "
        "errors from an aided start (initial_pos_m, initial_vel_m_s, initial_att_deg: 1-sigma per axis) with each "
        "term's share, as the list 'outage'; align=SECONDS a stationary alignment first (covariance model). model: 'paper', 'schuler', 'covariance', 'montecarlo' "
        "(comma string or list); signed_constants: the Monte Carlo takes bias and R as signed values, the same in "
        "every run (default: random constants per axis with that standard deviation, as the covariance). Returns the dict of `imunoise nav --format json`; each model's series "
        "(t_s, lat_deg, lon_deg, path_m, north_m, east_m, radial_m, ...) are NumPy arrays.");
}

}  // namespace imunoise::python
