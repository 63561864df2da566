#pragma once
// Each sensor's noise while the unit moves: the N-cornered hat in parity space
// (docs/redundant.md, "In-motion noise").
//
// The parity p = V m (V H = 0, V V^T = I, k = n - rank H rows) cancels the body motion, so p
// holds only the sensors' own errors. Integrated to phase, the overlapping Allan covariance of
// parity channels j and l at tau = m tau0 over N phase samples is
//   C_jl(tau) = 1 / (2 tau^2 (N - 2m)) sum_t d_j(t) d_l(t),  d(t) = x(t + 2m) - 2 x(t + m) + x(t),
// and for independent sensor errors its expectation is V diag(a(tau)) V^T, a_i the Allan
// variance of sensor i. The k (k + 1) / 2 distinct entries c = vech(C) are linear in a:
// c = A a, A_(jl),i = V_ji V_li. When A has rank n (every sensor identifiable) a is the
// non-negative generalised least-squares solution with the covariance of c of a Wishart matrix
// of nu degrees of freedom (the sample covariance of k channels sharing one noise spectrum):
//   Cov(C_jl, C_mn) = (C_jm C_ln + C_jn C_lm) / nu,
// evaluated at the model C = V diag(a) V^T (iterated from the unweighted solution), nu the
// Greenhall-Riley EDF of oadev for the noise type identified on the parity (confidence/edf.hpp).
// The estimates' covariance is (A^T Sigma^-1 A)^-1. For three co-aligned sensors (k = 2, three
// equations, three unknowns) the solution is the classical three-cornered hat of Gray & Allan
// (1974), a_1 = (s12 + s13 - s23) / 2 with s_ij the Allan variance of m_i - m_j, to rounding
// (tests/redundant/test_in_motion.cpp), the weights then playing no part.
//
// Intervals: each estimate is a linear combination of Wishart entries, treated as a scaled
// chi-squared of nu_i = 2 a_i^2 / var(a_i) degrees of freedom (Satterthwaite), the same
// chi-squared interval a direct oadev gets from its EDF (confidence/interval.hpp); an estimate
// at the bound 0 gets [0, sqrt(z sd)] with z the two-sided normal quantile. Coverage measured
// by the Monte Carlo of tests/redundant (SlowInMotionCoverage), reported in docs/redundant.md.
//
// Identifiability: every sensor has its own curve exactly when rank A = n, which needs
// k (k + 1) / 2 >= n: three co-aligned sensors per axis (n = 9, k = 6), six or more general
// sensors in general position (the dodecahedral six-gyro unit: k = 3, six equations, rank 6; the
// symmetric six-axis cone cone:6:DEG has rank 5 at every half-angle: its two interleaved triads
// at azimuths 0/120/240 and 60/180/300 deg give the same parity covariance, so only their
// difference is lost; seven or more on a cone: rank n). Four or five sensors give fewer
// equations than sensors (the tetrahedron: one equation): then only combinations are
// identified, and what is always reported is
//   trace(C) / k = sum_i w_i a_i,  w_i = |v_i|^2 / k (v_i column i of V, sum w_i = 1),
// the weighted mean of the sensors' Allan variances (the tetrahedron: the plain mean of the
// four), which is each sensor's Allan variance only under the assumption that all have the
// same noise; EDF k nu under that assumption.
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::redundant {

struct InMotionOptions {
  TauGrid grid;            ///< averaging times (default octave), clipped to oadev's domain
  double ci_level = 0.683; ///< two-sided confidence level of the intervals
  /// Throw InputError (with the reason) when the geometry cannot give every sensor its own
  /// curve, instead of returning only the identifiable combination.
  bool require_per_sensor = false;
  int gls_iterations = 3;  ///< re-weightings of the generalised least squares (>= 1)
  /// Estimate the motion leaking into the parity (scale-factor and misalignment errors) by
  /// regression on the fused motion and remove it before the noise analysis (Leakage).
  bool remove_leakage = true;
  /// With remove_leakage: also regress on the fused motion's derivative and curvature over one
  /// sample (central differences), which removes the leakage of sensors sampled at slightly
  /// different instants or through different filter delays (Leakage::time_offset_ms). On for
  /// the instances of one container, each on its own clock (study::container_unit).
  bool remove_timing_leakage = false;
};

/// The motion leaking into the parity through the sensors' scale-factor and misalignment
/// errors. Sensor i measuring (h_i + d_i) . w leaks p = V D w (D rows d_i). Each parity channel
/// is regressed on the fused motion w^ = G m (with an intercept), G weighted by the sensors'
/// white noise (their in-motion Allan variance at tau0; equal weights when not identifiable):
/// then the parity noise V e is uncorrelated with the fused noise G e (V R G^T = V H (...) = 0),
/// so a recording at rest gives coefficients ~ 0 instead of absorbing noise. The fitted B = V D
/// (k x c) is removed: p <- p - B w^.
/// What the parity sees of D is only its component in V's row space: D and D + H X (any c x c
/// X, a distortion of the whole unit's frame) leak alike. The per-sensor figures are therefore
/// those of the minimum-norm D^ = V^T B = P D (P = V^T V), "relative to the unit's best-fit
/// frame": a single sensor's 1000 ppm on the dodecahedral unit shows as P_ii 1000 = 500 ppm on
/// it and the rest spread over the others (tests/redundant/test_in_motion_validation.cpp).
///
/// Timing (InMotionOptions::remove_timing_leakage): sensor i sampling the motion dt_i late leaks
/// V diag(dt) H w' + V diag(dt^2 / 2) H w''; the parity is also regressed on the fused motion's
/// central first and second differences, and time_offset_ms[i] = 1e3 (V^T B_1)_i . h_i (the
/// minimum-norm offsets, relative to the unit: an offset common to every sensor does not reach
/// the parity). The differences carry the fused noise, high-passed: removing B_1 w^' adds to the
/// parity about (dt / tau0)^2 / 2 of the fused white-noise variance at tau0 (at most 1/8 for half
/// a sample), falling as 1 / tau^2 (docs/redundant.md).
/// g-sensitivity (a specific force given): gyro i reading g_i . f (rad/s per m/s^2) leaks
/// V Gs f; the parity is regressed on the fused specific force too, and g_sensitivity[i] is row
/// i of V^T B_f (minimum norm, relative to the unit like D), with its standard error.
/// Standard errors: from the regression's residual covariance S (k x k) and (X^T X)^-1, the
/// residuals taken white (Cov(vec B) = S (x) (X^T X)^-1): a lower bound for coloured noise.
struct Leakage {
  bool removed = false;
  bool timing = false;                     ///< regressed on the motion's derivative too
  bool g_sensitivity_estimated = false;    ///< a specific force was given
  Matrix coefficients;                     ///< B (k x c): parity per unit body rate
  std::vector<std::vector<double>> relative_error;  ///< rows of D^ = V^T B (n x c)
  std::vector<double> scale_factor_ppm;    ///< 1e6 d^_i . h_i (c = 3), or 1e6 d^_i (c = 1)
  std::vector<double> misalignment_mrad;   ///< 1e3 |d^_i - (d^_i . h_i) h_i| (0 when c < 3)
  double motion_rms_rad_s = 0.0;           ///< RMS of the fused motion (minus its mean)
  std::vector<double> time_offset_ms;      ///< per sensor, when timing (relative to the unit)
  /// Per sensor, rad/s per m/s^2 (x, y, z of the body), with standard errors; when estimated.
  std::vector<std::array<double, 3>> g_sensitivity_rad_s_per_m_s2;
  std::vector<std::array<double, 3>> g_sensitivity_se_rad_s_per_m_s2;
  double specific_force_rms_m_s2 = 0.0;    ///< RMS of the fused specific force (minus its mean)
};

/// What a parity space can identify about its sensors' Allan variances.
struct Identifiability {
  std::size_t sensors = 0;          ///< n
  std::size_t parity_channels = 0;  ///< k = rows of V
  std::size_t equations = 0;        ///< k (k + 1) / 2 distinct Allan covariances
  std::size_t rank = 0;             ///< rank of the map a -> vech(V diag(a) V^T)
  bool per_sensor = false;          ///< rank == n: every sensor its own curve
  std::string reason;               ///< why not (empty when per_sensor)
  /// w_i = |v_i|^2 / k: trace(C) / k = sum_i w_i a_i (empty when k = 0).
  std::vector<double> common_weights;
  /// A basis (unit vectors of n) of the unobservable changes of a: a + t u gives the same
  /// parity covariance for every t (empty when per_sensor). The six-axis symmetric cone:
  /// (1, -1, 1, -1, 1, -1) / sqrt 6, its two interleaved triads cannot be told apart.
  std::vector<std::vector<double>> unobservable;
};

/// The identifiability of a parity matrix V (k x n, orthonormal rows).
Identifiability identifiability(const Matrix& parity);

/// The parity matrix of a measurement matrix H (n x c, any c >= 1, rank c): V (n - c rows).
/// H of one column (1, 1, 1) is three co-aligned sensors: the classical three-cornered hat.
Matrix parity_of(const Matrix& measurement);

/// The overlapping Allan covariance matrix (k x k, unit^2) of k phase series of equal length
/// N (unit s) spaced tau0_s apart, at averaging factor m (1 <= m <= (N - 1) / 2).
Matrix allan_covariance(std::span<const std::span<const double>> phase, double tau0_s, std::size_t m);

/// One averaging time of the estimate.
struct InMotionPoint {
  std::size_t m = 0;
  double tau_s = 0.0;
  std::size_t n = 0;              ///< terms averaged (N - 2m)
  int alpha = 0;                  ///< noise type used for the EDF (confidence/edf.hpp)
  double edf_parity = 0.0;        ///< nu of the Wishart model
  Matrix allan_covariance;        ///< C (k x k), SI unit^2
  std::vector<double> estimate;   ///< a_i (n), SI unit^2; empty unless per_sensor
  Matrix estimate_covariance;     ///< Cov(a) (n x n), unit^4; empty unless per_sensor
  double common = 0.0;            ///< trace(C) / k, unit^2
  double common_variance = 0.0;   ///< its variance under equal noise, 2 common^2 / (k nu)
};

struct InMotionResult {
  Identifiability identifiability;
  Matrix parity;                  ///< V used
  double rate_hz = 0.0;
  std::size_t samples = 0;        ///< rate samples per sensor
  double ci_level = 0.683;
  std::vector<InMotionPoint> points;
  /// Each sensor's in-motion Allan deviation (SI; ci from the Satterthwaite EDF, in `edf`);
  /// empty unless identifiability.per_sensor.
  std::vector<std::vector<DevPoint>> sensors;
  /// sqrt(trace(C) / k) per tau with its interval (EDF k nu): the weighted mean level.
  std::vector<DevPoint> common;
  Leakage leakage;                ///< removed when options.remove_leakage
  std::vector<std::string> notes;
};

/// The in-motion analysis of n synchronous rate records (one span per sensor, SI, equal
/// lengths, the rows of `measurement` in the same order) sampled at rate_hz. With
/// `specific_force_m_s2` (three spans x, y, z of the body, the length of the records: the unit's
/// fused accelerometers) and remove_leakage, the gyros' g-sensitivity is estimated and removed
/// (Leakage). InputError for a count or length mismatch, fewer than 8 samples, no parity space,
/// or (options.require_per_sensor) a geometry that cannot identify every sensor.
InMotionResult in_motion_noise(const Matrix& measurement, std::span<const std::span<const double>> sensors_si,
                               double rate_hz, const InMotionOptions& options = {},
                               std::span<const std::span<const double>> specific_force_m_s2 = {});

/// The same for a geometry (H = measurement_matrix(geometry)).
InMotionResult in_motion_noise(const Geometry& geometry, std::span<const std::span<const double>> sensors_si,
                               double rate_hz, const InMotionOptions& options = {},
                               std::span<const std::span<const double>> specific_force_m_s2 = {});

/// Non-negative least squares min |A x - b|, x >= 0 (Lawson-Hanson active set), A rows x cols
/// row-major. Exact for the small dense systems here (cols <= a few dozen).
std::vector<double> nonnegative_least_squares(const Matrix& a, std::span<const double> b);

}  // namespace imunoise::redundant
