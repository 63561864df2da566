#pragma once
// Noise-model exports for the tools that consume them: a Kalibr `imu.yaml` and a JSON set of
// Kalman-filter process-noise parameters.
//
// Units. Kalibr's continuous-time white-noise strength `gyroscope_noise_density` (rad/s/sqrt(Hz))
// is the Allan angle random walk N (rad/sqrt(s)): 1/sqrt(Hz) = sqrt(s), and Kalibr's density is
// the square root of the two-sided PSD, as N is (spec.hpp). `gyroscope_random_walk`
// (rad/s^2/sqrt(Hz)) is the Allan rate random walk K (rad/s/sqrt(s)). For an accelerometer:
// `accelerometer_noise_density` = VRW N in m/s^2/sqrt(Hz), `accelerometer_random_walk` = K in
// m/s^3/sqrt(Hz). Example (references.md): N = 8.9e-4 deg/sqrt(s) = 0.0534 deg/sqrt(h)
// = 1.553e-5 rad/sqrt(s) = gyroscope_noise_density 1.553e-5.
//
// Numbers are written in the shortest form that reads back to the same double (round trip
// exact), with a decimal point so that YAML 1.1 readers (PyYAML, used by Kalibr) read floats.
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/noise_coefficients.hpp"

namespace imunoise {

/// The text of a Kalibr imu.yaml (keys gyroscope_noise_density, gyroscope_random_walk,
/// accelerometer_noise_density, accelerometer_random_walk, update_rate, rostopic).
/// Every value written is measured value x `inflation` (Kalibr's wiki advises inflating the
/// Allan values for unmodelled effects); comments give the units, the inflation factor and
/// the raw measured values with their confidence intervals.
/// A term that is absent (no accelerometer given, or a coefficient not identified) is NOT
/// invented: its key is written commented out with a "<FILL IN>" placeholder and the reason, so
/// Kalibr stops with a missing-key error instead of silently using a made-up number.
/// @param gyro        gyroscope coefficients (quantity angular_rate), SI
/// @param accel       accelerometer coefficients (quantity acceleration), SI, or nullptr
/// @param rate_hz     IMU sample rate (Hz), written as update_rate; > 0
/// @param inflation   factor applied to every noise value (> 0; 1 = raw values)
/// @param topic       rostopic, e.g. "/imu0" (empty -> "/imu0")
/// Throws InputError for a wrong quantity or a non-positive rate or inflation.
std::string kalibr_imu_yaml(const NoiseCoefficients& gyro, const NoiseCoefficients* accel,
                            double rate_hz, double inflation, std::string_view topic);

/// Kalman-filter process-noise parameters of one sensor axis, every number with its unit
/// ({"value": x, "unit": "..."}); the state is the sensor's rate (rad/s or m/s^2).
///  - white_noise: N; continuous PSD q = N^2 (rad^2/s, i.e. (rad/s)^2/Hz, two-sided);
///    discrete per-sample sigma N/sqrt(dt) (rad/s).
///  - bias_instability as a first-order Gauss-Markov process b' = -b/T_c + w:
///    sigma_GM, T_c, driving PSD 2 sigma_GM^2/T_c, discrete phi = exp(-dt/T_c) and
///    sigma_d = sigma_GM sqrt(1 - phi^2). When the fit identified a Gauss-Markov term it is used
///    as is. Otherwise the GM is the one whose Allan-deviation peak equals the bias-instability
///    floor (IEEE 952 Annex C; references.md: the GM Allan deviation peaks at 0.6174 sigma_GM,
///    "0.618" there, at tau = 1.8926 T_c; the floor is sqrt(2 ln 2/pi) B = 0.6643 B):
///      sigma_GM = sqrt(2 ln 2/pi) B / 0.6174 (= 1.0760 B),  T_c = tau_floor / 1.8926,
///    with tau_floor = `bias_floor_tau_s` if given, else the bottom of the N + K model,
///    tau_opt = sqrt(3) N / K (paper eq. 1). Without either, T_c is null with a note.
///  - rate_random_walk: K; PSD K^2 (rad^2/s^3); discrete random-walk step sigma K sqrt(dt).
///  - gauss_markov_states: the filter's Gauss-Markov states, one per entry, ordered by
///    correlation time: every Gauss-Markov term the fit identified (gmwm may fit several;
///    bias_instability then holds the first), else the one matched to B above (or none).
/// @param rate_hz sample rate (Hz) for the discrete values; > 0
/// @param bias_floor_tau_s averaging time (s) of the Allan floor, when known from the curve
nlohmann::json kalman_parameters(const NoiseCoefficients& coefficients, double rate_hz,
                                 std::optional<double> bias_floor_tau_s = std::nullopt);

/// The Allan deviation of a first-order Gauss-Markov process (sigma in rate units, T_c in s)
/// at averaging time tau (s): IEEE 952 Annex C,
///   sigma_A^2 = (2 sigma^2 T_c / tau) [1 - T_c/(2 tau) (3 - 4 e^{-tau/T_c} + e^{-2 tau/T_c})].
double gauss_markov_adev(double sigma, double correlation_time_s, double tau_s);

/// What a format without Gauss-Markov and sinusoid fields (Kalibr and the filter targets) drops
/// from `c`: one sentence per kind of term (every identified GM term with sigma (SI) and T_c;
/// the sinusoid), naming `format`. Empty when nothing is dropped. The exports write these as
/// comments and the command line as warnings.
std::vector<std::string> not_carried(const NoiseCoefficients& c, std::string_view format);

/// Shortest decimal text that reads back to exactly `value`, always with a '.' in the mantissa
/// ("3.0e-05", "200.0"); "nan"/"inf" for non-finite values.
std::string round_trip_number(double value);

/// Peak of the Gauss-Markov Allan deviation: adev_max = kGaussMarkovPeakRatio * sigma at
/// tau = kGaussMarkovPeakTau * T_c (computed to 4 digits; tests check them against
/// gauss_markov_adev).
inline constexpr double kGaussMarkovPeakRatio = 0.6174;
inline constexpr double kGaussMarkovPeakTau = 1.8926;

}  // namespace imunoise
