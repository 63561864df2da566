#include "imunoise/export/orbslam3.hpp"

#include <fmt/core.h>

#include "text.hpp"

namespace imunoise::exports {

std::string orbslam3_yaml(const ExportModel& model) {
  check_export_model(model, "--export orbslam3");
  const double f = model.inflation;
  const auto* stop = "ORB-SLAM3 aborts on a missing IMU key: fill it in from the datasheet";
  std::string out = "%YAML:1.0\n";
  out += detail::measured_header(model, "ORB-SLAM3 IMU settings (fragment)", "#");
  out +=
      "# Continuous-time values (Kalibr's units); ORB-SLAM3 discretises them with IMU.Frequency\n"
      "# (src/Tracking.cc: noise x sqrt(freq), walk / sqrt(freq)). Copy into the settings file\n"
      "# beside IMU.T_b_c1 (the camera-IMU transform is not measured by imunoise).\n\n";
  out += detail::key_line("", "IMU.NoiseGyro", detail::scaled(model.gyro, &NoiseCoefficients::random_walk, 1.0, f, "N"),
                          "rad/s/sqrt(Hz) = N", stop);
  out += detail::key_line("", "IMU.NoiseAcc", detail::scaled(model.accel, &NoiseCoefficients::random_walk, 1.0, f, "N"),
                          "m/s^2/sqrt(Hz) = N", stop);
  out += detail::key_line("", "IMU.GyroWalk",
                          detail::scaled(model.gyro, &NoiseCoefficients::rate_random_walk, 1.0, f, "K"),
                          "rad/s^2/sqrt(Hz) = K", stop);
  out += detail::key_line("", "IMU.AccWalk",
                          detail::scaled(model.accel, &NoiseCoefficients::rate_random_walk, 1.0, f, "K"),
                          "m/s^3/sqrt(Hz) = K", stop);
  out += fmt::format("IMU.Frequency: {}  # Hz, the IMU sample rate\n", detail::number(model.rate_hz));
  return out;
}

}  // namespace imunoise::exports
