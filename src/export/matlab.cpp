#include "imunoise/export/matlab.hpp"

#include <fmt/core.h>

#include "text.hpp"

namespace imunoise::exports {
namespace {

std::string sensor(const ExportModel& m, bool gyro) {
  const auto& s = gyro ? m.gyro : m.accel;
  const char* var = gyro ? "gyro" : "accel";
  const char* rate = gyro ? "rad/s" : "m/s^2";
  std::string out = fmt::format("{} = {}params;\n", var, var);
  const auto* zero = "the toolbox default is 0 (an ideal sensor): fill it in";
  const auto line = [&](const char* prop, Coefficient NoiseCoefficients::*term, const char* symbol,
                        const std::string& unit) {
    return detail::key_line("", fmt::format("{}.{}", var, prop),
                            detail::scaled(s, term, 1.0, m.inflation, symbol), unit + " = " + symbol,
                            zero, "%", " = ", ";");
  };
  out += line("NoiseDensity", &NoiseCoefficients::random_walk, "N", fmt::format("({})/sqrt(Hz)", rate));
  out += line("RandomWalk", &NoiseCoefficients::rate_random_walk, "K", fmt::format("({})*sqrt(Hz)", rate));
  out += line("BiasInstability", &NoiseCoefficients::bias_instability, "B", rate);
  out += fmt::format("{}.NoiseType = \"double-sided\";  % N is the square root of the two-sided PSD\n", var);
  return out;
}

}  // namespace

std::string matlab_script(const ExportModel& model) {
  check_export_model(model, "--export matlab");
  std::string out = detail::measured_header(model, "MATLAB gyroparams / accelparams script", "%");
  out +=
      "% Continuous-time values; imuSensor discretises them at its SampleRate f (white noise std\n"
      "% NoiseDensity sqrt(f) for \"double-sided\", walk step RandomWalk / sqrt(f)). BiasInstability\n"
      "% is the Allan floor coefficient B (floor = 0.664 B, IEEE 952).\n\n";
  out += sensor(model, true) + "\n" + sensor(model, false) + "\n";
  out += fmt::format("% imu = imuSensor(\"accel-gyro\", \"SampleRate\", {}, \"Gyroscope\", gyro, "
                     "\"Accelerometer\", accel);\n",
                     detail::number(model.rate_hz));
  return out;
}

}  // namespace imunoise::exports
