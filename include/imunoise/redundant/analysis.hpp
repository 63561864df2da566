#pragma once
// What a redundant gyro unit achieves: the weighted least-squares fusion of its n sensors into
// body rates, the fused axes' noise, the parity space and what fault detection can see.
//
// Equations (docs/redundant.md; Sturza 1988; Daly, Gai & Harrison 1979):
//   m = H w + e,  e ~ N(0, R), R = diag(N_i^2)/tau0 (each sensor's white noise);
//   w^ = G m,  G = (H^T W H)^-1 H^T W,  W = R^-1 (or I when no models are given);
//   geometric covariance P = (H^T H)^-1: per-axis gain sqrt(P_jj), GDOP sqrt(trace P);
//   parity V (k x n, k = n - 3): V H = 0, V V^T = I; p = V m does not depend on w.
// The fused axes' noise terms: every term of the sensors' models (Q, N, B, K, R) is
// independent between sensors, so term c of axis j is c_j^2 = sum_i G_ji^2 c_i^2 (for identical
// sensors on the tetrahedron: 0.8660 c). Checked against the closed forms of
// ../shared/references.md and against simulated units fitted by `fit` (tests/redundant).
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "imunoise/noise_coefficients.hpp"
#include "imunoise/redundant/geometry.hpp"

namespace imunoise::redundant {

/// One sensor's identified noise model (from `fit` of that gyro), SI (rad/s based).
struct SensorModel {
  std::string source;  ///< where it came from (fit file name), for messages
  NoiseCoefficients coefficients;
};

/// Fault detection settings (detection.hpp has the test itself).
struct DetectionOptions {
  /// Test window (s): the mean of the last window is compared with the reference mean.
  double window_s = 1.0;
  /// Reference window (s) just before the test window; its mean follows slow drift (bias,
  /// bias instability, rate random walk) so that only a change is tested. Rounded to a whole
  /// number of test windows.
  double reference_s = 60.0;
  /// Configured false-alarm rate (alarms per hour of clean data). One test per window, so the
  /// per-test probability is false_alarm_per_hour * window_s / 3600.
  double false_alarm_per_hour = 0.01;
  /// Probability of detecting the minimum detectable fault (within one test).
  double detection_probability = 0.99;
  /// Onset resolution: the window is split into this many blocks for the change-point estimate.
  int blocks_per_window = 20;
  /// An isolated fault removes its sensor from the later tests (false: keep testing all
  /// sensors, e.g. to count raw alarms).
  bool exclude_isolated = true;

  /// Checks every field (positive, finite, probabilities in (0, 1), reference >= window,
  /// per-test probability < 0.5); writes why not into *error (may be null).
  bool IsValid(std::string* error) const;
};

/// What a detection setting implies for this unit (independent of the sample rate).
struct DetectionDesign {
  double window_s = 0.0;
  double reference_s = 0.0;
  double false_alarm_per_hour = 0.0;
  double tests_per_hour = 0.0;        ///< 3600 / window_s
  double per_test_probability = 0.0;  ///< false_alarm_per_hour / tests_per_hour
  std::size_t dof = 0;                ///< k = n - 3 (chi-squared degrees of freedom)
  double threshold = 0.0;             ///< chi2_k upper quantile at per_test_probability
  double detection_probability = 0.0;
  double noncentrality = 0.0;         ///< lambda detected with detection_probability
  /// Standard deviation of (window mean - reference mean) of each sensor's noise (rad/s):
  /// N^2 (1/a + 1/b) + K^2 (a + b)/3 + Q^2 (1/a^2 + (1/a + 1/b)^2 + 1/b^2) + B^2 F(a, b)
  /// with a = window_s, b = reference_s and F the flicker integral (flicker_difference_variance).
  std::vector<double> sigma_difference_rad_s;
  /// The whitened parity matrix Vw (k x n) of Hw = S^-1 H, S = diag(sigma_difference): the test
  /// statistic is |Vw S^-1 (window mean - reference mean)|^2 ~ chi2_k without a fault.
  Matrix whitened_parity;
};

struct AnalysisOptions {
  DetectionOptions detection;
  /// Weight the fusion by the sensors' white noise (W = diag(1/N_i^2)) when models are given;
  /// false: equal weights.
  bool weight_by_noise = true;
};

struct Analysis {
  Geometry geometry;
  Matrix measurement;                 ///< H, n x 3
  Matrix fusion;                      ///< G, 3 x n: w^ = G m
  bool weighted = false;              ///< G uses the sensors' white noise
  Matrix geometric_covariance;        ///< (H^T H)^-1, 3 x 3 (unit sensor noise)
  std::array<double, 3> axis_gain{};  ///< sqrt of its diagonal: fused noise / one sensor's
  double gdop = 0.0;                  ///< sqrt of its trace
  Matrix parity;                      ///< V, k x n
  bool detectable = false;            ///< k >= 1: a single fault can be detected
  /// k >= 2 and no two sensors' parity columns are parallel: a single fault can be isolated.
  bool isolable = false;
  /// Degraded unit without sensor i (nullopt: the others do not span 3-D).
  std::vector<std::optional<std::array<double, 3>>> axis_gain_without;
  std::vector<std::optional<double>> gdop_without;

  std::vector<SensorModel> sensors;   ///< as given (empty: geometry only)
  /// The fused body axes' noise (x, y, z), SI; present when sensors are given.
  std::optional<std::array<NoiseCoefficients, 3>> axes;
  DetectionDesign detection;          ///< thresholds; sigma and MDF need sensors
  /// Per sensor: the smallest step bias (rad/s) detected with detection_probability in one
  /// test; NaN without models, +inf when the sensor is not in the parity space.
  std::vector<double> min_detectable_fault_rad_s;
  /// The same in multiples of that sensor's white noise over one window, N_i / sqrt(window_s),
  /// for the white-noise-only case: sqrt(lambda (1 + a/b)) / |v_i| (needs no model).
  std::vector<double> min_detectable_fault_window_sigma;
  std::vector<std::string> notes;
};

/// The analysis of a geometry, optionally with one noise model per sensor (same order).
/// InputError when the number of models differs from the number of axes or options are bad.
Analysis analyze_unit(const Geometry& geometry, std::span<const SensorModel> sensors = {},
                      const AnalysisOptions& options = {});

/// The detection design for given per-sensor noise (needed by the detector): window and
/// reference as given (the detector passes the values rounded to whole samples).
DetectionDesign design_detection(const Geometry& geometry, std::span<const SensorModel> sensors,
                                 const DetectionOptions& options);

/// Variance factor F(a, b) of a unit flicker (B = 1) rate noise, two-sided PSD 1/(2 pi f), for
/// the difference of its mean over a window of a seconds and its mean over the b seconds just
/// before: F = (1/pi) [(a+b)^2/(ab) ln(a+b) - (1/a + 1/b)(b ln b + a ln a)] (closed form from
/// the angle's structure function -(1/pi) tau^2 ln tau), equal to the frequency-domain integral
/// (1/pi) int |H(f)|^2 df/f, |H|^2 = sa^2 + sb^2 - 2 sa sb cos(pi f (a+b)), s = sinc (checked in
/// tests/redundant). For a = b = tau: 4 ln 2 / pi, twice the Allan variance of flicker.
double flicker_difference_variance(double a_s, double b_s);

/// Orthonormal basis of the left null space of M (n x 3): rows V with V M = 0, V V^T = I.
/// Deterministic: Gram-Schmidt of the projector's columns in sensor order, so the first
/// non-zero entry of each row is positive (tetra: (1, -1, 1, -1)/2).
Matrix parity_basis(const Matrix& m);

}  // namespace imunoise::redundant
