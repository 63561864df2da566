#include "imunoise/export/ros.hpp"

#include <cmath>

#include <fmt/core.h>

#include "text.hpp"

namespace imunoise::exports {
namespace {

std::string array_line(const char* key, const detail::Value& v, const char* unit) {
  if (!v.value) {
    return fmt::format("# {}: <FILL IN>  # {} -- NOT MEASURED by imunoise: {}; fill in, or set element 0 "
                       "to -1 (\"not provided\")\n",
                       key, unit, v.why_absent);
  }
  const std::string d = detail::number(*v.value);
  return fmt::format("{}: [{}, 0.0, 0.0, 0.0, {}, 0.0, 0.0, 0.0, {}]  # {} = N^2 f{}\n", key, d, d, d, unit,
                     detail::interval_text(v));
}

}  // namespace

std::string ros_covariance_yaml(const ExportModel& model) {
  check_export_model(model, "--export ros");
  const double f = model.rate_hz;
  std::string out = detail::measured_header(model, "ROS sensor_msgs/Imu covariance diagonals", "#");
  out += fmt::format(
      "# Variance of ONE sample at the IMU rate f = {} Hz (row-major 3x3, x y z): N^2 f.\n"
      "# The message has no place for the bias random walk or instability (see the measured lines).\n",
      detail::number(f));
  auto var = [&](const std::optional<SensorModel>& s) {
    return detail::squared(detail::scaled(s, &NoiseCoefficients::random_walk, std::sqrt(f), model.inflation, "N"));
  };
  out += array_line("angular_velocity_covariance", var(model.gyro), "rad^2/s^2");
  out += array_line("linear_acceleration_covariance", var(model.accel), "m^2/s^4");
  return out;
}

}  // namespace imunoise::exports
