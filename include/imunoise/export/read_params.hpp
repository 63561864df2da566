#pragma once
// Reads a user's parameter file of any export target back into numbers: the keys of
// target_keys() as written (the consumer's own units). The target is given or recognised from
// the file (extension .params / .m / .json, or the YAML keys: imu0 -> openvins, IMU.NoiseGyro
// -> orbslam3, gyr_n -> vins, angular_velocity_covariance -> ros, gyroscope_noise_density ->
// kalibr). YAML is read with yaml-cpp after OpenCV's "%YAML:1.0" first line.
#include <optional>
#include <string>
#include <vector>

#include "imunoise/export/target_keys.hpp"

namespace imunoise::exports {

struct ParamValue {
  KeySpec spec;
  double value = 0.0;  ///< as written in the file
};

struct ParamsFile {
  std::string path;
  Target target = Target::kalibr;
  bool target_detected = false;  ///< true: recognised from the file, not given
  std::vector<ParamValue> values;  ///< the target's keys present in the file, in table order
  std::vector<std::string> missing;  ///< the target's keys absent (or commented out)
  std::optional<double> rate_hz;     ///< the rate the file states (update_rate, IMU.Frequency)
};

/// Throws InputError naming the file (and the line or key) for an unreadable file, a target
/// that cannot be recognised ("... give --target T; targets: kalibr openvins ..."), a value that
/// is not a number, a ROS covariance whose diagonal differs between axes, or a file with none
/// of the target's keys.
ParamsFile read_params_file(const std::string& path, std::optional<Target> target = std::nullopt);

/// The same from text (`name` for messages).
ParamsFile read_params_text(const std::string& text, const std::string& name,
                            std::optional<Target> target = std::nullopt);

}  // namespace imunoise::exports
