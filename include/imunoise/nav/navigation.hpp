#pragma once
// Navigation error growth: what the gyro and accelerometer noise does to a free-inertial
// navigation system.
//
// Four models, each computing the 1-sigma (RMS) error of latitude, longitude, the position
// along each level axis (north, east; `path` = north, the paper's "path") and the horizontal
// radial error sqrt(sigma_N^2 + sigma_E^2), versus time, from the noise of three gyros and three
// accelerometers whose axes are aligned with north (x), east (y) and down (z) on a level,
// stationary platform. The horizontal channels are modelled; the down accelerometer drives the
// vertical channel only (unstable in free inertial, not modelled) and is left out, said in the
// notes.
//
//  - paper      : the paper's eq. 6 as published (paper.hpp), with the sigma_eps it takes;
//  - schuler    : single-channel Schuler-loop closed forms per noise term (schuler.hpp), the
//                 east gyro and the north accelerometer driving the north channel (latitude,
//                 path), the north gyro and the east accelerometer the east channel
//                 (longitude); independent terms add in variance; no Earth rate;
//  - covariance : the linearised NED error model of both horizontal channels and the azimuth,
//                 with Earth rate and Coriolis coupling (error_model.hpp), propagated exactly
//                 in discrete time (Van Loan matrix exponential) with the noise as states;
//  - montecarlo : the same linear model driven by the project's simulator (sim/generator.hpp),
//                 many seeded runs on threads, RMS and mean with their sampling errors.
//
// Noise: every term of NoiseCoefficients (Q, N, B, K, R, Gauss-Markov) plus a constant bias, for
// each gyro and each accelerometer (for an accelerometer N is the velocity random walk, K the
// acceleration random walk, Q the velocity quantization).
// Bias instability B is flicker noise realised, in every model alike, as the simulator's
// documented bank of Gauss-Markov processes (sim/flicker.hpp) over [dt_s, duration_s]: the
// Allan floor 0.6643 B is honoured there to 0.1 %. Deterministic terms (bias, ramp) have an
// unknown sign: they enter as random variables of RMS |bias|, |R|, so the reported errors are
// RMS over sign as well.
//
// Units: SI inside (rad, rad/s, m, s); the JSON document (report.hpp) converts at the edge.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "imunoise/nav/earth.hpp"
#include "imunoise/noise_coefficients.hpp"

namespace imunoise::nav {

enum class Model { paper, schuler, covariance, montecarlo };
/// "paper", "schuler", "covariance", "montecarlo".
const char* model_name(Model model);
/// Parses a comma list of model names (also "all"); InputError naming an unknown one.
std::vector<Model> parse_models(const std::string& list);

/// The noise of one gyro axis: the identified coefficients (SI; a term with identified ==
/// false or value 0 is absent) and a constant drift.
struct GyroAxisNoise {
  NoiseCoefficients coefficients;
  double bias_rad_s = 0.0;  ///< constant drift (rad/s), sign irrelevant: enters as RMS |bias|
};

/// One first-order Gauss-Markov rate noise: stationary sigma (the sensor's SI rate unit: rad/s
/// for a gyro, m/s^2 for an accelerometer) and correlation time (s).
struct GaussMarkovNoise {
  double sigma = 0.0;
  double time_s = 0.0;
};

/// Root-sum-square of the sigmas (0: no Gauss-Markov term).
double gauss_markov_rss(const std::vector<GaussMarkovNoise>& terms);

/// The noise terms of one axis as plain SI numbers, after the choice of what is present.
struct GyroTerms {
  double q_rad = 0.0;                ///< Q: angle (quantization) noise (rad)
  double n_rad_sqrt_s = 0.0;         ///< N: angle random walk (rad/sqrt(s))
  double b_rad_s = 0.0;              ///< B: bias instability (rad/s)
  double k_rad_s_sqrt_s = 0.0;       ///< K: rate random walk (rad/s/sqrt(s))
  double r_rad_s2 = 0.0;             ///< R: rate ramp (rad/s^2)
  /// Every identified first-order Gauss-Markov term (sigma in rad/s), by correlation time.
  std::vector<GaussMarkovNoise> gauss_markov;
  double bias_rad_s = 0.0;           ///< constant drift (rad/s)
};

/// Present terms of an axis (value of identified coefficients only).
GyroTerms terms_of(const GyroAxisNoise& axis);

/// The noise of one accelerometer axis (coefficients in SI: m/s^2 is the rate unit) and a
/// constant bias (m/s^2, sign irrelevant as for the gyros).
struct AccelAxisNoise {
  NoiseCoefficients coefficients = [] {
    NoiseCoefficients c;
    c.quantity = Quantity::acceleration;
    return c;
  }();
  double bias_m_s2 = 0.0;
};

/// The noise terms of one accelerometer axis as plain SI numbers.
struct AccelTerms {
  double q_m_s = 0.0;              ///< Q: velocity quantization (m/s)
  double n_m_s_sqrt_s = 0.0;       ///< N: velocity random walk (m/s/sqrt(s))
  double b_m_s2 = 0.0;             ///< B: bias instability (m/s^2)
  double k_m_s2_sqrt_s = 0.0;      ///< K: acceleration random walk (m/s^2/sqrt(s))
  double r_m_s3 = 0.0;             ///< R: acceleration ramp (m/s^3)
  /// Every identified first-order Gauss-Markov term (sigma in m/s^2), by correlation time.
  std::vector<GaussMarkovNoise> gauss_markov;
  double bias_m_s2 = 0.0;          ///< constant bias (m/s^2)
};

AccelTerms terms_of(const AccelAxisNoise& axis);

struct NavOptions {
  /// Gyro noise of the x (north), y (east) and z (down) axes.
  std::array<GyroAxisNoise, 3> axes;
  /// Accelerometer noise of the same axes (default: none).
  std::array<AccelAxisNoise, 3> accel_axes;
  double duration_s = 3600.0;    ///< operating time (s) > 0
  double step_s = 60.0;          ///< reporting interval (s); a multiple of dt_s
  double dt_s = 1.0;             ///< propagation / simulation step (s)
  double latitude_rad = 0.0;     ///< |latitude| <= pi/2; at the pole longitude is undefined
  double velocity_m_s = 0.0;     ///< ground speed, only for the distance travelled (see docs)
  bool earth_rate = true;        ///< covariance/montecarlo: Earth rate and Coriolis terms
  std::vector<Model> models{Model::schuler, Model::covariance};
  std::size_t runs = 1000;       ///< Monte-Carlo runs
  std::uint64_t seed = 1;        ///< Monte-Carlo seed
  /// montecarlo: the constant drift and the rate ramp of each axis as given, signed and the
  /// same in every run. Default (false): each run draws them per axis as independent random
  /// constants with that standard deviation, the question the covariance and Schuler models
  /// answer (a drift of unknown sign), so that every model gives the same RMS.
  bool signed_constants = false;
  unsigned threads = 0;          ///< Monte-Carlo threads (0: hardware); results do not depend on it
  /// paper model: sigma_eps (rad/s); unset: the paper's reading, N's value taken as a rate
  /// (N in deg/sqrt(s) read as deg/s), east axis.
  std::optional<double> paper_sigma_eps_rad_s;
  EarthModel earth;
  /// Stationary alignment before navigation (s; 0: a perfect start, the default): the
  /// covariance model holds position and velocity at zero for align_s seconds (zero-velocity
  /// and zero-position updates, a Kalman filter on the same error model) and navigates from the
  /// posterior: levelling by the accelerometers, gyrocompassing by the Earth rate, with the
  /// correlations between the attitude and the sensor errors that alignment leaves (an
  /// accelerometer bias is then cancelled by the tilt it caused). Covariance model and outages only.
  double align_s = 0.0;
  /// Length (s) of the shortest record the noise was measured on (0: unknown): a horizon beyond
  /// it extrapolates the long-term terms, which a note says.
  double measured_s = 0.0;
  /// GNSS outage horizons (s; empty: none) and the 1-sigma errors the aiding left at the
  /// outage start, per axis (outage.hpp).
  std::vector<double> outage_s;
  double initial_pos_m = 0.0;
  double initial_vel_m_s = 0.0;
  double initial_att_rad = 0.0;
  /// covariance: propagate every dt step between reported times instead of composing the
  /// step by doubling (same result to rounding; the baseline of bench/bench_nav.cpp).
  bool covariance_per_step = false;

  /// False with a message naming the field and the fix.
  bool IsValid(std::string* why) const;
};

/// Monte-Carlo statistics beside the RMS series (all in m, per reported time).
struct MonteCarloStats {
  std::size_t runs = 0;
  std::uint64_t seed = 0;
  std::vector<double> mean_north_m, mean_east_m;       ///< sample means
  std::vector<double> se_mean_north_m, se_mean_east_m; ///< their standard errors
  std::vector<double> se_rms_north_m, se_rms_east_m, se_rms_radial_m;  ///< SE of each RMS
  /// Mean squares and their standard errors (m^2): the quantities the statistical test uses.
  std::vector<double> ms_north_m2, se_ms_north_m2, ms_east_m2, se_ms_east_m2;
};

/// Health of the propagated covariance at the final time (covariance model only).
struct CovarianceCheck {
  std::size_t states = 0;            ///< dimension of the augmented state
  double max_asymmetry = 0.0;        ///< max |P - P'| / max |P| (0: symmetric)
  double min_eigenvalue_ratio = 0.0; ///< smallest eigenvalue / largest (>= -1e-12: PSD)
};

/// One model's error growth; every vector has one value per reported time.
struct ModelSeries {
  Model model = Model::schuler;
  std::string assumptions;           ///< the model and what it assumes, in words
  std::vector<double> t_s;
  std::vector<double> lat_rad;       ///< RMS latitude error (rad)
  std::vector<double> lon_rad;       ///< RMS longitude error (rad); empty at the pole
  std::vector<double> north_m;       ///< RMS position error along north = path (m)
  std::vector<double> east_m;        ///< RMS position error along east (m)
  std::vector<double> radial_m;      ///< horizontal radial RMS (m)
  std::optional<MonteCarloStats> montecarlo;
  std::optional<CovarianceCheck> covariance_check;
  double paper_sigma_eps_rad_s = 0.0;  ///< paper model only: the sigma_eps used
  /// covariance only: each term's share of the horizontal position variance per reported time
  /// ("gyro N", "accel bias", ...; the shares add up to 1), in the order Q N B K R GM bias.
  std::vector<std::pair<std::string, std::vector<double>>> budget;
};

/// The errors at one GNSS-outage horizon (outage.hpp).
struct OutagePoint {
  double t_s = 0.0;
  double north_m = 0.0;
  double east_m = 0.0;
  double horizontal_m = 0.0;   ///< sqrt(north^2 + east^2)
  double velocity_m_s = 0.0;   ///< sqrt(sigma_vN^2 + sigma_vE^2)
  double attitude_rad = 0.0;   ///< sqrt(sigma_psiN^2 + sigma_psiE^2 + sigma_psiD^2)
  /// Each term's share of horizontal_m^2 ("gyro N", "accel bias", "initial attitude", ...),
  /// largest first; terms that contribute nothing are left out.
  std::vector<std::pair<std::string, double>> budget;
};

struct NavResult {
  NavOptions options;
  std::array<GyroTerms, 3> terms;          ///< what was used per gyro axis (SI)
  std::array<AccelTerms, 3> accel_terms;   ///< per accelerometer axis (SI)
  std::vector<std::string> absent_terms;   ///< e.g. "Q (all axes)", "R (x)"
  std::vector<std::string> notes;          ///< warnings: absent terms, undefined longitude, ...
  bool longitude_defined = true;
  std::vector<double> t_s;                 ///< reported times
  std::vector<ModelSeries> models;         ///< in the order asked
  /// The attitude errors (1-sigma, rad) left by the alignment (align_s > 0): tilt about north and
  /// east, heading.
  std::optional<std::array<double, 3>> alignment_rad;
  /// The outage errors at options.outage_s (outage.hpp), when asked.
  std::vector<OutagePoint> outage;
};

/// Runs every model asked. Throws InputError for invalid options (NavOptions::IsValid) or a
/// noise model with no term at all.
NavResult navigation_error(const NavOptions& options);

/// The reported times: 0, step, 2 step, ... <= duration, and duration itself.
std::vector<double> report_times(const NavOptions& options);

/// The published one-hour figures of the paper (Figures 5-7): 0.37 deg, 22.6 km, 3.9 deg.
struct PaperPublished {
  double t_s = 3600.0;
  double lat_deg = 0.37;
  double path_m = 22.6e3;
  double lon_deg = 3.9;
};

}  // namespace imunoise::nav
