#pragma once
// A simulated redundant unit under motion: each sensor's noise (the project's simulator, one
// independent stream per sensor), scale-factor and misalignment errors and noise that grows with
// the rate it senses, through any geometry, under a motion profile of turns and sinusoidal
// rotations (vibration lines). For the in-motion analysis (in_motion.hpp) and its validation.
//
// Sensor i outputs, for sample t (SI, rad/s):
//   m_i[t] = (1 + s_i) (h_i + d_i) . w_t + g_i . f_t + e_i[t] + c_i |h_i . w_t| u_i[t] / sqrt(tau0)
// with w_t the body rate averaged over the sample [t tau0 + dt_i, (t + 1) tau0 + dt_i] (exact for
// the profile's sines and constant: a rate gyro integrates; dt_i = time_offset_s, a sensor
// sampled late), s_i = scale_factor_ppm 1e-6, d_i the misalignment (its component along h_i
// removed, so it only tilts the axis), g_i the g-sensitivity (rad/s per m/s^2) on the specific
// force f_t (specific_force below), e_i the sensor's noise model, u_i unit white noise (its own
// stream) and c_i = motion_noise (sqrt(s)): a white noise of density c_i |h_i . w| (rad/s/sqrt(Hz))
// while the sensor turns at |h_i . w|.
#include <array>
#include <cstdint>
#include <span>
#include <string>
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
  /// Gravity (m/s^2) of the unit's specific force: +g along the world vertical, which the
  /// body sees turn as the body rotates (specific_force); 0: no gravity.
  double gravity_m_s2 = 9.80665;
  /// Linear vibration of the specific force in body axes (m/s^2), the same line form.
  std::vector<RotationLine> vibration_m_s2;

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
  double time_offset_s = 0.0;                ///< dt_i: samples the motion this late (s)
  std::array<double, 3> g_sensitivity_rad_s_per_m_s2{};  ///< g_i of the header
};

/// One record per sensor (rad/s), round(duration_s rate_hz) samples each. InputError for a
/// sensor count that differs from the geometry's, a line above the Nyquist frequency, or the
/// simulator's own checks (named by sensor).
std::vector<std::vector<double>> simulate_unit(const Geometry& geometry, std::span<const UnitSensor> sensors,
                                               const MotionProfile& motion, double rate_hz, double duration_s,
                                               std::uint64_t seed);

/// A motion profile from its text (the command line's --motion): terms joined by '+', each
///   still                 no rotation;
///   tumble[:DEG_S]        tumble_profile (default 200 deg/s);
///   turn:X,Y,Z            a steady turn (deg/s);
///   vibration:DEG_S:HZ    a vibration line of that amplitude on every axis (phases 0, 1, 2 rad).
/// InputError naming the term and the forms accepted.
MotionProfile motion_profile(std::string_view spec);

/// The noise model with every value in the unit U (Q, N, B, K, R, bias, Gauss-Markov sigma,
/// sinusoid amplitude) multiplied by `to_si`, for a model given in deg/s into rad/s.
sim::NoiseModel scaled_noise(sim::NoiseModel model, double to_si);

/// Writes sensor i's record (SI) to DIR/sensor<i>.txt (1-based), one value a line in the unit
/// `unit_name` (value / to_si, 17 significant digits) after '#' lines of `header` and the
/// sensor's axis; returns the paths. Each file is written atomically; InputError when one exists
/// without `force` (before any is written) or DIR cannot be created.
std::vector<std::string> write_unit_records(const std::string& dir, bool force, const Geometry& geometry,
                                            std::span<const std::vector<double>> records, const std::string& unit_name,
                                            double to_si, const std::string& header);

/// The unit's specific force in body axes (m/s^2; x, y, z, one record each, round(duration_s
/// rate_hz) samples): what a perfect accelerometer triad co-aligned with the body reads at
/// mid-sample, for a unit that rotates in place (no translation but the vibration lines). The
/// attitude starts level (body z up) and is propagated by the sample-mean body rate over each
/// sample (rotation vector w tau0; exact for a rate of constant direction); f = R^T (0, 0, g)
/// + vibration.
std::array<std::vector<double>, 3> specific_force(const MotionProfile& motion, double rate_hz, double duration_s);

}  // namespace imunoise::redundant
