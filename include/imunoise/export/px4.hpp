#pragma once
// PX4 EKF2 IMU noise parameters as a QGroundControl .params file (lines
// "vehicle<TAB>component<TAB>name<TAB>value<TAB>type", type 9 = float). EKF2 applies them per
// prediction step dt_e (src/modules/ekf2/EKF/covariance.cpp): delta-angle variance
// (dt_e EKF2_GYR_NOISE)^2, delta-velocity variance (dt_e EKF2_ACC_NOISE)^2, bias variance
// growth (dt_e EKF2_GYR_B_NOISE)^2 and (dt_e EKF2_ACC_B_NOISE)^2, with dt_e = EKF2_PREDICT_US
// (default 10000 us: 100 Hz). Matching the continuous model at f_e = 1/dt_e:
//   EKF2_GYR_NOISE = N sqrt(f_e) (rad/s),   EKF2_ACC_NOISE = N_a sqrt(f_e) (m/s^2),
//   EKF2_GYR_B_NOISE = K sqrt(f_e) (rad/s^2), EKF2_ACC_B_NOISE = K_a sqrt(f_e) (m/s^3).
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// Absent terms are comment lines (QGroundControl skips '#'). Throws InputError without any
/// sensor or for a non-positive EKF rate.
std::string px4_params(const ExportModel& model);

}  // namespace imunoise::exports
