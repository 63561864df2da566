#include "imunoise/export/openvins.hpp"

#include <fmt/core.h>

#include "text.hpp"

namespace imunoise::exports {
namespace {

std::string matrix(std::string_view key, int rows, int cols, bool identity) {
  std::string out = fmt::format("  {}:\n", key);
  for (int r = 0; r < rows; ++r) {
    out += "    - [";
    for (int c = 0; c < cols; ++c) out += fmt::format("{}{}", c ? ", " : "", identity && r == c ? "1.0" : "0.0");
    out += "]\n";
  }
  return out;
}

}  // namespace

std::string openvins_yaml(const ExportModel& model) {
  check_export_model(model, "--export openvins");
  detail::require_gyro(model, "openvins");
  const double f = model.inflation;
  const auto* stop = "OpenVINS stops on a missing key: fill it in from the datasheet";
  std::string out = "%YAML:1.0\n";
  out += detail::measured_header(model, "OpenVINS kalibr_imu_chain.yaml", "#");
  out +=
      "# Continuous-time values (Kalibr's units); OpenVINS discretises them at each step dt\n"
      "# (ov_msckf/src/state/Propagator.cpp): white noise sigma^2/dt, bias walk sigma_b^2 dt.\n"
      "# Intrinsics are identity (imunoise measures noise only): replace them with Kalibr's.\n\n";
  out += "imu0:\n";
  out += matrix("T_i_b", 4, 4, true);
  out += detail::key_line("  ", "accelerometer_noise_density",
                          detail::scaled(model.accel, &NoiseCoefficients::random_walk, 1.0, f, "N"),
                          "m/s^2/sqrt(Hz) = N (accel white noise)", stop);
  out += detail::key_line("  ", "accelerometer_random_walk",
                          detail::scaled(model.accel, &NoiseCoefficients::rate_random_walk, 1.0, f, "K"),
                          "m/s^3/sqrt(Hz) = K (accel bias diffusion)", stop);
  out += detail::key_line("  ", "gyroscope_noise_density",
                          detail::scaled(model.gyro, &NoiseCoefficients::random_walk, 1.0, f, "N"),
                          "rad/s/sqrt(Hz) = N (gyro white noise)", stop);
  out += detail::key_line("  ", "gyroscope_random_walk",
                          detail::scaled(model.gyro, &NoiseCoefficients::rate_random_walk, 1.0, f, "K"),
                          "rad/s^2/sqrt(Hz) = K (gyro bias diffusion)", stop);
  out += fmt::format("  rostopic: {}\n", model.topic.empty() ? "/imu0" : model.topic);
  out += "  time_offset: 0.0\n";
  out += fmt::format("  update_rate: {}  # Hz\n", detail::number(model.rate_hz));
  out += "  model: \"kalibr\"\n";
  out += matrix("Tw", 3, 3, true);
  out += matrix("R_IMUtoGYRO", 3, 3, true);
  out += matrix("Ta", 3, 3, true);
  out += matrix("R_IMUtoACC", 3, 3, true);
  out += matrix("Tg", 3, 3, false);
  return out;
}

}  // namespace imunoise::exports
