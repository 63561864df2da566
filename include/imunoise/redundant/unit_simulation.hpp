#pragma once
// A simulated redundant unit under motion: each sensor's noise (the project's simulator, one
// independent stream per sensor), scale-factor and misalignment errors and noise that grows with
// the rate it senses, through any geometry, under a motion profile of turns and sinusoidal
// rotations (vibration lines). For the in-motion analysis (in_motion.hpp) and its validation.
//
// Sensor i outputs, for sample t (SI, rad/s):
//   m_i[t] = (1 + s_i) (h_i + d_i) . w_t + e_i[t] + c_i |h_i . w_t| u_i[t] / sqrt(tau0)
// with w_t the body rate averaged over the sample (exact for the profile's sines and constant:
// a rate gyro integrates), s_i = scale_factor_ppm 1e-6, d_i the misalignment (its component
// along h_i removed, so it only tilts the axis), e_i the sensor's noise model, u_i unit white
// noise (its own stream) and c_i = motion_noise (sqrt(s)): a white noise of density c_i |h_i . w|
// (rad/s/sqrt(Hz)) while the sensor turns at |h_i . w|.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "imunoise/redundant/geometry.hpp"
#include "imunoise/sim/noise_model.hpp"

namespace imunoise::redundant {

/// A sinusoidal rotation about body axes: w(t) = amplitude sin(2 pi f t + phase) per axis.
struct RotationLine {
  std::array<double, 3> amplitude_rad_s{};
  double frequency_hz = 0.0;
  std::array<double, 3> phase_rad{};
};

struct MotionProfile {
  std::array<double, 3> constant_rad_s{};  ///< a steady turn
  std::vector<RotationLine> lines;         ///< rotations and vibration lines

  /// The body rate averaged over [t0_s, t0_s + duration_s] (exact), rad/s.
  [[nodiscard]] std::array<double, 3> mean_rate(double t0_s, double duration_s) const;
};

/// Rotations to `amplitude_rad_s` on all three axes at 0.5, 0.31 and 0.17 Hz (x, y, z; phases
/// 0, 1, 2 rad): incommensurate, so every direction of the parity leakage is excited.
MotionProfile tumble_profile(double amplitude_rad_s);

struct UnitSensor {
  sim::NoiseModel noise;                     ///< in rad/s (the model's unit U = rad/s)
  double scale_factor_ppm = 0.0;
  std::array<double, 3> misalignment_rad{};  ///< added to the axis; the part along it is ignored
  double motion_noise_sqrt_s = 0.0;          ///< c_i of the header
};

/// One record per sensor (rad/s), round(duration_s rate_hz) samples each. InputError for a
/// sensor count that differs from the geometry's, a line above the Nyquist frequency, or the
/// simulator's own checks (named by sensor).
std::vector<std::vector<double>> simulate_unit(const Geometry& geometry, std::span<const UnitSensor> sensors,
                                               const MotionProfile& motion, double rate_hz, double duration_s,
                                               std::uint64_t seed);

}  // namespace imunoise::redundant
