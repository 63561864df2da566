#pragma once
// What each key of a target's file means: which sensor and term, and how the consumer's value
// follows from the continuous coefficient (N or K, SI) — the discretisation documented in
// docs/exports.md and in each target's header. The parameter audit compares a user's file
// with the recording through this table; the export tests check the renderers against it.
#include <string>
#include <vector>

#include "imunoise/export/export_target.hpp"

namespace imunoise::exports {

enum class Sensor { gyro, accel };
enum class Term { white, walk };  ///< N (white noise) or K (bias random walk)

/// How the file's number follows from the coefficient c (N or K):
enum class Form {
  density,           ///< c itself (Kalibr's continuous units)
  discrete_imu,      ///< c sqrt(f), f = IMU rate (VINS)
  discrete_ekf,      ///< c sqrt(f_e), f_e = PX4's EKF rate
  psd,               ///< c^2 (GTSAM's continuous covariances)
  variance_imu,      ///< c^2 f (ROS: variance of one sample)
};

struct KeySpec {
  std::string key;   ///< as in the file: "gyroscope_noise_density", "IMU.NoiseGyro", ...
  Sensor sensor;
  Term term;
  Form form;
  std::string unit;  ///< unit of the file's number
};

/// The noise keys of a target's file (the ones imunoise writes and checks).
const std::vector<KeySpec>& target_keys(Target target);

/// The file's number for coefficient `c` (SI): the Form applied at `rate_hz` / `ekf_rate_hz`.
double file_value(Form form, double c, double rate_hz, double ekf_rate_hz);

/// "N sqrt(f)", "K^2", ... for messages.
std::string form_formula(Form form, Term term);

}  // namespace imunoise::exports
