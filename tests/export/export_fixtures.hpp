#pragma once
// Known noise models for the export tests: a gyro and an accelerometer triad with white noise N
// and bias random walk K of a MEMS IMU (the order of Kalibr's EuRoC values), at 200 Hz.
#include <optional>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports::test {

inline constexpr double kRateHz = 200.0;
inline constexpr double kGyroN = 2.0e-4;   // rad/s/sqrt(Hz)
inline constexpr double kGyroK = 2.0e-5;   // rad/s^2/sqrt(Hz)
inline constexpr double kGyroB = 1.0e-4;   // rad/s
inline constexpr double kAccelN = 2.0e-3;  // m/s^2/sqrt(Hz)
inline constexpr double kAccelK = 3.0e-4;  // m/s^3/sqrt(Hz)
inline constexpr double kAccelB = 5.0e-4;  // m/s^2

inline Coefficient known(double value) {
  Coefficient c;
  c.value = value;
  c.identified = true;
  c.ci_low = 0.9 * value;
  c.ci_high = 1.1 * value;
  return c;
}

inline SensorModel sensor(Quantity q, double n, double k, double b, const char* channels) {
  SensorModel s;
  s.coefficients.quantity = q;
  s.coefficients.random_walk = known(n);
  s.coefficients.rate_random_walk = known(k);
  if (b > 0.0) s.coefficients.bias_instability = known(b);
  s.channels = channels;
  s.selection = "per term the largest of 3 axes";
  return s;
}

/// Gyro + accelerometer, or (accel = false) the gyro alone.
inline ExportModel model(bool accel = true, double inflation = 1.0) {
  ExportModel m;
  m.gyro = sensor(Quantity::angular_rate, kGyroN, kGyroK, kGyroB, "gyro_x gyro_y gyro_z");
  if (accel) m.accel = sensor(Quantity::acceleration, kAccelN, kAccelK, kAccelB, "accel_x accel_y accel_z");
  m.rate_hz = kRateHz;
  m.inflation = inflation;
  m.source = "bench.bag";
  return m;
}

}  // namespace imunoise::exports::test
