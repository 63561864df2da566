#pragma once
// VINS-Fusion / VINS-Mono configuration fragment (OpenCV FileStorage, %YAML:1.0): acc_n,
// gyr_n, acc_w, gyr_w. These are DISCRETE per-sample values at the IMU rate f, not Kalibr's
// densities: the preintegration (vins_estimator/src/factor/integration_base.h) puts
// acc_n^2 / gyr_n^2 on each sample's noise and maps it with 0.5 dt (rotation) into the state,
// and acc_w^2 / gyr_w^2 on the bias with dt per step. Matching the continuous model:
//   gyr_n = N sqrt(f) (rad/s),  acc_n = N_a sqrt(f) (m/s^2),
//   gyr_w = K sqrt(f) (rad/s^2), acc_w = K_a sqrt(f) (m/s^3)
// (bias step gyr_w dt = K sqrt(dt), the random-walk step of K).
#include <string>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

/// Absent terms are commented placeholders. Throws InputError without any sensor.
std::string vins_yaml(const ExportModel& model);

}  // namespace imunoise::exports
