#include "imunoise/export/vins.hpp"

#include <cmath>

#include <fmt/core.h>

#include "text.hpp"

namespace imunoise::exports {

std::string vins_yaml(const ExportModel& model) {
  check_export_model(model, "--export vins");
  const double f = model.inflation;
  const double s = std::sqrt(model.rate_hz);
  const auto* zero =
      "VINS reads a missing key as 0 WITHOUT a warning: fill it in before use";
  std::string out = "%YAML:1.0\n";
  out += detail::measured_header(model, "VINS-Fusion / VINS-Mono IMU noise (config fragment)", "#");
  out += fmt::format(
      "# DISCRETE per-sample values at the IMU rate f = {} Hz (sqrt(f) = {:.6g}), not Kalibr's\n"
      "# densities: vins_estimator/src/factor/integration_base.h puts acc_n^2, gyr_n^2 on each\n"
      "# sample and acc_w^2, gyr_w^2 on the bias per step of dt. So *_n = N sqrt(f), *_w = K sqrt(f).\n"
      "# Copy these keys into the estimator's config (it needs imu: 1 and its other keys).\n\n",
      detail::number(model.rate_hz), s);
  out += detail::key_line("", "acc_n", detail::scaled(model.accel, &NoiseCoefficients::random_walk, s, f, "N"),
                          "m/s^2, accelerometer sample noise std = N sqrt(f)", zero);
  out += detail::key_line("", "gyr_n", detail::scaled(model.gyro, &NoiseCoefficients::random_walk, s, f, "N"),
                          "rad/s, gyroscope sample noise std = N sqrt(f)", zero);
  out += detail::key_line("", "acc_w",
                          detail::scaled(model.accel, &NoiseCoefficients::rate_random_walk, s, f, "K"),
                          "m/s^3, accelerometer bias walk = K sqrt(f) (step acc_w dt)", zero);
  out += detail::key_line("", "gyr_w",
                          detail::scaled(model.gyro, &NoiseCoefficients::rate_random_walk, s, f, "K"),
                          "rad/s^2, gyroscope bias walk = K sqrt(f) (step gyr_w dt)", zero);
  return out;
}

}  // namespace imunoise::exports
