#include "imunoise/nav/request.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/units.hpp"

namespace imunoise::nav {
namespace {

// "--hours" on the command line, "hours" in Python.
std::string option(const CoefficientNames& names, std::string name) {
  std::replace(name.begin(), name.end(), '-', names.separator);
  return names.prefix + name;
}

Unit gyro_unit(const NavRequest& r) {
  const Unit unit = parse_unit(r.units);
  if (unit.quantity != Quantity::angular_rate) {
    throw InputError(fmt::format("{} {} is not an angular rate ({}): the navigation error needs gyro coefficients, "
                                 "e.g. deg/s, rad/s or deg/h",
                                 option(r.names, "units"), r.units, quantity_name(unit.quantity)));
  }
  return unit;
}

std::array<GyroAxisNoise, 3> axes_of(const NavRequest& r, const Unit& unit) {
  const auto fitted = std::count_if(r.fitted_axes.begin(), r.fitted_axes.end(), [](const auto& a) { return a.has_value(); });
  if (fitted > 0 && r.coefficients_given) {
    const auto o = [&](const char* name) { return option(r.names, name); };
    throw InputError(fmt::format("give the noise either as coefficients ({} {} {} {} {}, {} {}) or as fits ({} or {}), "
                                 "not both ({} may be added to either)",
                                 o("Q"), o("N"), o("B"), o("K"), o("R"), o("gm-sigma"), o("gm-tau"), r.fit_option,
                                 r.per_axis_fit_option, o("bias")));
  }
  if (fitted != 0 && fitted != 3) {
    throw InputError(fmt::format("give fits for all three axes ({}: x north, y east, z down), or one fit for every "
                                 "axis ({})", r.per_axis_fit_option, r.fit_option));
  }
  std::array<GyroAxisNoise, 3> axes;
  const GyroAxisNoise common = axis_from_coefficients(r.coefficients, unit, r.names);
  for (std::size_t a = 0; a < 3; ++a) axes[a] = fitted ? *r.fitted_axes[a] : common;
  for (auto& a : axes) a.bias_rad_s = r.bias * unit.to_si;
  return axes;
}

// The accelerometers' noise, the same on every axis; named "--accel-N" or "accel_N".
std::array<AccelAxisNoise, 3> accel_axes_of(const NavRequest& r) {
  const Unit unit = parse_unit(r.accel_units);
  if (unit.quantity != Quantity::acceleration) {
    throw InputError(fmt::format("{} {} is not an acceleration ({}): give the accelerometer unit as m/s^2, g, mg or ug",
                                 option(r.names, "accel-units"), r.accel_units, quantity_name(unit.quantity)));
  }
  if (!std::isfinite(r.accel_bias)) throw InputError(option(r.names, "accel-bias") + " must be finite");
  CoefficientNames names = r.names;
  names.prefix = option(r.names, "accel-");
  AccelAxisNoise axis;
  axis.coefficients = axis_from_coefficients(r.accel_coefficients, unit, names).coefficients;
  axis.coefficients.quantity = Quantity::acceleration;
  axis.bias_m_s2 = r.accel_bias * unit.to_si;
  const auto& c = r.accel_coefficients;
  const bool given = c.q != 0 || c.n != 0 || c.b != 0 || c.k != 0 || c.r != 0 || c.gm_sigma != 0;
  std::array<AccelAxisNoise, 3> axes{axis, axis, axis};
  bool fitted = false;
  for (std::size_t a = 0; a < 3; ++a) {
    if (!r.fitted_accel_axes[a]) continue;
    fitted = true;
    axes[a].coefficients = r.fitted_accel_axes[a]->coefficients;
  }
  if (fitted && given) {
    throw InputError(fmt::format("give the accelerometer noise either as coefficients ({}N ...) or from the study "
                                 "({}), not both", option(r.names, "accel-"), r.fit_option));
  }
  if (fitted) {
    for (std::size_t a = 0; a < 3; ++a) {
      if (r.fitted_accel_axes[a]) continue;
      axes[a].coefficients = NoiseCoefficients{};
      axes[a].coefficients.quantity = Quantity::acceleration;
    }
  }
  return axes;
}

}  // namespace

NavOptions plan_navigation(const NavRequest& r) {
  const Unit unit = gyro_unit(r);
  if (!std::isfinite(r.bias)) throw InputError(option(r.names, "bias") + " must be finite");
  if (!(r.hours > 0.0) || !std::isfinite(r.hours)) {
    throw InputError(option(r.names, "hours") + " must be positive (the operating time in hours)");
  }
  if (!(std::abs(r.latitude_deg) <= 90.0)) {
    throw InputError(fmt::format("{} {:g} is beyond +-90 deg; give the latitude in degrees within [-90, 90]",
                                 option(r.names, "latitude"), r.latitude_deg));
  }
  NavOptions o;
  o.axes = axes_of(r, unit);
  o.accel_axes = accel_axes_of(r);
  o.outage_s = r.outage_s;
  o.measured_s = r.measured_s;
  o.align_s = r.align_s;
  o.initial_pos_m = r.initial_pos_m;
  o.initial_vel_m_s = r.initial_vel_m_s;
  o.initial_att_rad = r.initial_att_deg * std::numbers::pi / 180.0;
  o.duration_s = r.hours * 3600.0;
  o.step_s = std::min(r.step_s, o.duration_s);
  o.dt_s = r.dt_s;
  o.latitude_rad = r.latitude_deg * std::numbers::pi / 180.0;
  o.velocity_m_s = r.velocity_m_s;
  o.earth_rate = r.earth_rate;
  o.models = parse_models(r.models);
  o.runs = r.runs;
  o.seed = r.seed;
  o.signed_constants = r.signed_constants;
  o.threads = r.threads;
  if (r.sigma_eps) o.paper_sigma_eps_rad_s = *r.sigma_eps * unit.to_si;
  return o;
}

}  // namespace imunoise::nav
