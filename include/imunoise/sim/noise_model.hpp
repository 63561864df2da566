#pragma once
// The noise model of one sensor channel: every term of the Allan-variance model (IEEE Std
// 952-1997 Annex C; the paper's eq. 5 and its seven components) with its intensity.
//
// Units. The simulator is unit-agnostic: every parameter is expressed in the unit system of
// the channel's rate, written U below (deg/s for the paper's gyros; rad/s, m/s^2, g or a
// fractional frequency work the same way), and samples come out in U. Field names carry the
// dimension: q_unit_s is in U*s (deg for U = deg/s), n_unit_sqrt_s in U*sqrt(s) (deg/sqrt(s)),
// b_unit in U (deg/s), k_unit_per_sqrt_s in U/sqrt(s) (deg/s/sqrt(s)), r_unit_per_s in U/s
// (deg/s^2). These are the units of the paper's Table 2 and of the `fit` output.
//
// What a sample is. Sample k is the average of the continuous-time rate over
// [k tau0, (k+1) tau0) (an integrating sensor), so the angle tau0 * sum(samples) equals the
// exact integral of the rate at every sample instant. Consequently the Allan variance of the
// simulated sequence at tau = m tau0 equals the continuous-time Allan variance of the model
// at that tau, and the closed forms of theory.hpp hold exactly, not only asymptotically.
#include <cstdint>
#include <limits>

namespace imunoise::sim {

struct NoiseModel {
  /// Q: angle (quantization) noise, U*s. Modelled as white noise on the angle at the sample
  /// instants with standard deviation Q, so sigma^2(tau) = 3 Q^2 / tau^2 at every tau = m tau0.
  double q_unit_s = 0.0;
  /// N: angle random walk, U*sqrt(s). White rate noise of two-sided PSD N^2;
  /// per-sample standard deviation N / sqrt(tau0); sigma^2(tau) = N^2 / tau.
  double n_unit_sqrt_s = 0.0;
  /// B: bias instability, U. Flicker (1/f) rate noise of two-sided PSD B^2 / (2 pi f) whose
  /// Allan floor is sqrt(2 ln 2 / pi) B = 0.66428 B over [flicker_tau_min_s, flicker_tau_max_s]
  /// (realised by the Gauss-Markov bank of flicker.hpp; accuracy stated there).
  double b_unit = 0.0;
  /// K: rate random walk, U/sqrt(s). The rate is K times a Wiener process started at 0;
  /// sigma^2(tau) = K^2 tau / 3.
  double k_unit_per_sqrt_s = 0.0;
  /// R: rate ramp, U/s (signed: the slope of the rate); sigma^2(tau) = R^2 tau^2 / 2.
  double r_unit_per_s = 0.0;
  /// First-order Gauss-Markov (Ornstein-Uhlenbeck) rate noise: stationary standard deviation
  /// gm_sigma_unit (U) and correlation time gm_time_s (s); started in its stationary state.
  double gm_sigma_unit = 0.0;
  double gm_time_s = 0.0;
  /// Sinusoid A sin(2 pi f t + phase) added to the rate (A in U, f in Hz, phase in rad, t = 0
  /// at the start of sample 0). Needs f <= rate / 2.
  double sine_amplitude_unit = 0.0;
  double sine_frequency_hz = 0.0;
  double sine_phase_rad = 0.0;
  /// Constant bias, U (signed).
  double bias_unit = 0.0;
  /// The tau range over which the flicker floor is honoured (s). 0 means the default: one
  /// sample interval for the lower end and the record duration (at least 10 tau_min) for the
  /// upper end; the generator fills both in (see resolve_flicker_range) and theory.hpp needs
  /// them set.
  double flicker_tau_min_s = 0.0;
  double flicker_tau_max_s = 0.0;
};

/// What happens to the rate on its way out of the sensor, in this order: saturation at the
/// measurement range, scale factor and offset (e.g. volts for an analog output), and an ADC
/// quantizer. Defaults leave the rate untouched.
struct OutputStage {
  /// Measurement range: the rate is clipped to [-range_unit, +range_unit] (U); inf = none.
  double range_unit = std::numeric_limits<double>::infinity();
  /// Output units per U: 1 for output in U; 0.02 for the TG-100's 20 mV/(deg/s) analog output
  /// in volts; 1 + e for a scale-factor error e. Non-zero; may be negative.
  double scale_factor = 1.0;
  /// Added after scaling, in output units (e.g. the zero-rate output voltage).
  double offset_output = 0.0;
  /// ADC step in output units: the output is rounded to the nearest multiple (ties to even).
  /// 0 = no quantizer. Its error is deterministic; for signals much busier than the step it
  /// behaves like white noise of variance lsb^2/12 per sample, which theory.hpp does not add.
  double lsb_output = 0.0;
};

/// Throws InputError naming the field when a parameter is negative where it must not be, not
/// finite, or inconsistent (a Gauss-Markov sigma without a correlation time, a flicker range
/// with tau_min >= tau_max). Sampling-dependent checks are done by check_sampling.
void validate(const NoiseModel& model);
void validate(const OutputStage& output);

/// Checks what depends on the sample rate and the duration: rate and duration positive and
/// finite, at least one sample, the sinusoid below the Nyquist frequency, and a flicker range
/// the generator can honour (lower end >= one sample interval; at most flicker_max_decades).
void check_sampling(const NoiseModel& model, double rate_hz, double duration_s);

/// The model with its flicker range defaults filled in: tau_min = 1/rate_hz and
/// tau_max = max(duration_s, 10 tau_min) where they are 0. Other fields are copied unchanged.
NoiseModel resolve_flicker_range(NoiseModel model, double rate_hz, double duration_s);

/// True when the model has no random and no deterministic term at all.
bool is_silent(const NoiseModel& model);

}  // namespace imunoise::sim
