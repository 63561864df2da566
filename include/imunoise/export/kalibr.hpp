#pragma once
// Kalibr's imu.yaml (https://github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model): continuous-time
// values, gyroscope_noise_density = N (rad/s/sqrt(Hz)), gyroscope_random_walk = K
// (rad/s^2/sqrt(Hz)), accelerometer_* likewise in m/s^2/sqrt(Hz) and m/s^3/sqrt(Hz); Kalibr
// discretises them itself at update_rate f: sigma_d = N sqrt(f), sigma_bd = K / sqrt(f).
// The text is spec/exports.hpp's kalibr_imu_yaml under a header saying what was measured.
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// Kalibr imu.yaml. Throws InputError without a gyro model (Kalibr's file is a gyro file
/// first; its accelerometer keys are placeholders when no accelerometer was measured).
std::string kalibr_yaml(const ExportModel& model);

}  // namespace imunoise::exports
