#pragma once
// OpenVINS' kalibr_imu_chain.yaml (OpenCV FileStorage, %YAML:1.0, everything under imu0):
// T_i_b (identity), accelerometer_noise_density, accelerometer_random_walk,
// gyroscope_noise_density, gyroscope_random_walk (Kalibr's continuous units), rostopic,
// time_offset (0), update_rate, model "kalibr" with identity intrinsics (Tw, R_IMUtoGYRO, Ta,
// R_IMUtoACC, zero Tg): noise is all imunoise measures. OpenVINS discretises at each
// propagation step dt (ov_msckf/src/state/Propagator.cpp): white noise sigma^2 / dt, bias
// walk sigma_b^2 dt.
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// Throws InputError without a gyro model.
std::string openvins_yaml(const ExportModel& model);

}  // namespace imunoise::exports
