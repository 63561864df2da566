#pragma once
// Single-channel Schuler loop: closed forms of the position error caused by each gyro noise
// term (Titterton & Weston, Strapdown Inertial Navigation Technology, 2nd ed., ch. 12;
// references.md).
//
// Model: a level axis whose gyro drifts by eps(t); position angle th (path S = R th),
// velocity error v, tilt phi:  th' = v / R,  v' = g phi,  phi' = -v / R - eps.
// The impulse response from eps to th is h(u) = -(1 - cos w0 u), w0 = sqrt(g / R), so
//   th(t) = -int_0^t (1 - cos w0 (t - s)) eps(s) ds.
// Each function returns the RMS of th(t) in rad (multiply by R for metres):
//   constant drift c:  |c| (t - sin(w0 t)/w0)
//   rate ramp r:       |r| (t^2/2 - (1 - cos w0 t)/w0^2)
//   white rate N:      N sqrt(1.5 t - 2 sin(w0 t)/w0 + sin(2 w0 t)/(4 w0))
//   rate random walk K:K sqrt(int_0^t (u - sin(w0 u)/w0)^2 du)
//                      = K sqrt(t^3/3 - 2 (sin w0t - w0t cos w0t)/w0^3 + t/(2 w0^2)
//                                - sin(2 w0 t)/(4 w0^3))
//   Gauss-Markov (sigma, T), started stationary: sigma^2 int int h(a) h(b) e^{-|a-b|/T},
//                      summed exactly over the exponentials of h (complex arithmetic);
//   quantization Q:    white angle noise of RMS Q at the sample instants k h (the simulator's
//                      model), i.e. eps_k = (q_{k+1} - q_k)/h piecewise constant; with
//                      A_m = int_{(m-1)h}^{mh} (1 - cos w0 u) du and t = k h,
//                      var = (Q/h)^2 [A_1^2 + A_k^2 + (4 sin^2(w0 h/2)/w0)^2 sum_{m<k} sin^2(w0 m h)].
// An accelerometer error f (m/s^2) enters the velocity: v' = g phi + f. Its impulse response to
// th is h_f(u) = sin(w0 u) / (R w0) = -h'(u) / g, so with x = w0 t (RMS of th, rad):
//   constant bias c:   |c| (1 - cos x) / g             (bounded: the Schuler oscillation)
//   ramp r:            |r| (x - sin x) / (g w0)
//   white (VRW) N:     N / (R w0) sqrt(t/2 - sin(2x) / (4 w0))
//   random walk K:     the gyro white form with N = K / g (f' white drives th like eps / g)
//   Gauss-Markov:      as for the gyro, over the exponentials of h_f
//   quantization Q:    white velocity noise of RMS Q at the sample instants; with
//                      C_m = 4 sin^2(w0 h/2) cos(w0 m h) / (R w0^2) and B_m the step integrals,
//                      var = (Q/h)^2 [B_1^2 + B_k^2 + sum_{m<k} C_m^2].
// Accuracy: relative 1e-12 or better where w0 t >= 0.5. For w0 t < 1 the closed forms cancel
// (the response grows like t^3 to t^7 while the terms grow like t), so the constant-drift,
// ramp, white and random-walk forms switch to their power series there (relative 1e-14). The
// Gauss-Markov form has no such switch: below w0 t ~ 0.5 its absolute error is ~1e-16 of
// sigma^2 t^2 (micrometres for any real gyro), and it is clamped at 0, never negative.
namespace imunoise::nav::schuler {

/// Schuler frequency sqrt(g / R) (rad/s).
double frequency_rad_s(double gravity_m_s2, double radius_m);

double constant_drift_rad(double bias_rad_s, double t_s, double w0_rad_s);
double rate_ramp_rad(double ramp_rad_s2, double t_s, double w0_rad_s);
double white_rad(double n_rad_sqrt_s, double t_s, double w0_rad_s);
double random_walk_rad(double k_rad_s_sqrt_s, double t_s, double w0_rad_s);
double gauss_markov_rad(double sigma_rad_s, double time_s, double t_s, double w0_rad_s);
/// t_s must be a multiple of the sample interval h_s (rounded to the nearest one).
double quantization_rad(double q_rad, double h_s, double t_s, double w0_rad_s);

/// Accelerometer terms (m/s^2 based units; R the radius, g = R w0^2).
double accel_bias_rad(double bias_m_s2, double t_s, double w0_rad_s, double radius_m);
double accel_ramp_rad(double ramp_m_s3, double t_s, double w0_rad_s, double radius_m);
double accel_white_rad(double n_m_s_sqrt_s, double t_s, double w0_rad_s, double radius_m);
double accel_random_walk_rad(double k_m_s2_sqrt_s, double t_s, double w0_rad_s, double radius_m);
double accel_gauss_markov_rad(double sigma_m_s2, double time_s, double t_s, double w0_rad_s, double radius_m);
double accel_quantization_rad(double q_m_s, double h_s, double t_s, double w0_rad_s, double radius_m);

/// Tilt (attitude) error RMS caused by a constant drift: |c| sin(w0 t) / w0 (rad); for docs.
double constant_drift_tilt_rad(double bias_rad_s, double t_s, double w0_rad_s);

}  // namespace imunoise::nav::schuler
