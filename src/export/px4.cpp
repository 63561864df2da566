#include "imunoise/export/px4.hpp"

#include <cmath>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "text.hpp"

namespace imunoise::exports {

std::string px4_params(const ExportModel& model) {
  check_export_model(model, "--export px4");
  const double fe = model.px4_ekf_rate_hz;
  if (!(std::isfinite(fe) && fe > 0.0)) {
    throw InputError(fmt::format("--export px4: EKF prediction rate {:g} Hz is not positive", fe));
  }
  const double s = std::sqrt(fe);
  std::string out = "# Onboard parameters for Vehicle 1\n";
  out += detail::measured_header(model, "PX4 EKF2 IMU noise parameters (QGroundControl .params)", "#");
  out += fmt::format(
      "# EKF2 applies these once per prediction step dt_e (src/modules/ekf2/EKF/covariance.cpp:\n"
      "# delta-angle variance (dt_e EKF2_GYR_NOISE)^2, bias growth (dt_e EKF2_GYR_B_NOISE)^2), so\n"
      "# they are discrete values at the EKF rate f_e = 1e6/EKF2_PREDICT_US = {} Hz (PX4's\n"
      "# default EKF2_PREDICT_US 10000): *_NOISE = N sqrt(f_e), *_B_NOISE = K sqrt(f_e).\n"
      "# If EKF2_PREDICT_US differs on the vehicle, re-export for its rate. PX4 clamps each to 0..1.\n"
      "# Lines starting with '#' are skipped by QGroundControl; absent values are such lines.\n"
      "#\n"
      "# Vehicle-Id\tComponent-Id\tName\tValue\tType\n",
      detail::number(fe));
  struct Param {
    const char* name;
    bool gyro;
    Coefficient NoiseCoefficients::*term;
    const char* symbol;
    const char* unit;
  };
  constexpr Param params[] = {
      {"EKF2_GYR_NOISE", true, &NoiseCoefficients::random_walk, "N", "rad/s"},
      {"EKF2_ACC_NOISE", false, &NoiseCoefficients::random_walk, "N", "m/s^2"},
      {"EKF2_GYR_B_NOISE", true, &NoiseCoefficients::rate_random_walk, "K", "rad/s^2"},
      {"EKF2_ACC_B_NOISE", false, &NoiseCoefficients::rate_random_walk, "K", "m/s^3"},
  };
  for (const auto& p : params) {
    const auto v = detail::scaled(p.gyro ? model.gyro : model.accel, p.term, s, model.inflation, p.symbol);
    if (v.value) {
      out += fmt::format("# {} = {} sqrt(f_e) in {}{}{}\n", p.name, p.symbol, p.unit, detail::interval_text(v),
                         *v.value > 1.0 ? " (ABOVE PX4's clamp of 1: the EKF will use 1)" : "");
      out += fmt::format("1\t1\t{}\t{}\t9\n", p.name, detail::number(*v.value));
    } else {
      out += fmt::format("# 1\t1\t{}\t<FILL IN>\t9  ({} -- NOT MEASURED by imunoise: {}; the vehicle keeps its "
                         "current value)\n",
                         p.name, p.unit, v.why_absent);
    }
  }
  return out;
}

}  // namespace imunoise::exports
