#pragma once
// ORB-SLAM3 settings fragment (OpenCV FileStorage, %YAML:1.0): IMU.NoiseGyro, IMU.NoiseAcc,
// IMU.GyroWalk, IMU.AccWalk (continuous, Kalibr's units) and IMU.Frequency (Hz). ORB-SLAM3
// discretises them itself (src/Tracking.cc: sf = sqrt(IMU.Frequency), IMU::Calib(Ng sf, Na sf,
// Ngw / sf, Naw / sf)); src/ImuTypes.cc adds the walk covariance once per measurement.
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// Absent terms are commented placeholders. Throws InputError without any sensor.
std::string orbslam3_yaml(const ExportModel& model);

}  // namespace imunoise::exports
