#pragma once
// First-order Gauss-Markov (Ornstein-Uhlenbeck) rate noise, sampled exactly.
//
// The process w(t) has stationary standard deviation sigma and correlation time T:
// dw = -w/T dt + sqrt(2 sigma^2 / T) dW, autocovariance sigma^2 exp(-|t|/T), two-sided PSD
// 2 sigma^2 T / (1 + (2 pi f T)^2). Over one sample interval h the pair (state at the end,
// average over the interval) given the state at the start is jointly Gaussian; its exact
// moments give the update
//     average  = a w + b z1 + c z2
//     w_next   = phi w + s z1
// with z1, z2 independent N(0, 1), x = h/T, phi = e^-x:
//     s = sigma sqrt(1 - phi^2),  a = (1 - phi)/x,  b = sigma (1 - phi)^2 / (x sqrt(1 - phi^2)),
//     c = (sigma/x) sqrt(2 g(x) - (1 - phi)^3/(1 + phi)),  g(x) = x - 3/2 + 2 e^-x - e^-2x / 2.
// So simulated samples have exactly the statistics of the continuous process averaged over
// each interval, for any T (from T << h, where it is white, to T >> h, where it is a random
// walk), and its Allan variance is the closed form below at every tau = m h.
// Coefficients are computed with portable:: functions, identically on every platform; g is
// evaluated by its Taylor series for x < 1, so no precision is lost when T >> h.

namespace imunoise::sim {

/// g(x) = x - 3/2 + 2 e^-x - e^-2x / 2 (= x^3/3 - x^4/4 + ... for small x), x >= 0,
/// to within a few ulp relative.
double gauss_markov_g(double x);

/// Allan variance (U^2) of Gauss-Markov noise (sigma in U, time_s = T in s) at tau_s:
/// 2 sigma^2 g(x) / x^2 with x = tau/T; equal to IEEE 952's
/// (q_c T^2 / tau) [1 - T/(2 tau) (3 - 4 e^-x + e^-2x)], q_c = 2 sigma^2 / T.
/// Asymptotes: 2 sigma^2 tau / (3 T) (a rate random walk) for tau << T,
/// 2 sigma^2 T / tau (white noise) for tau >> T; peak 0.617364 sigma at tau = 1.89262 T
/// (references.md rounds it to 0.618 sigma at 1.89 T).
double gauss_markov_allan_variance(double sigma_unit, double time_s, double tau_s);

/// Two-sided PSD (U^2/Hz) at frequency f_hz >= 0: 2 sigma^2 T / (1 + (2 pi f T)^2).
double gauss_markov_psd(double sigma_unit, double time_s, double f_hz);

/// The exact one-interval update described above.
struct GaussMarkovStep {
  double phi = 0.0;           ///< state decay e^-h/T
  double state_noise = 0.0;   ///< s, U
  double mean_of_state = 0.0; ///< a, dimensionless
  double mean_of_z1 = 0.0;    ///< b, U
  double mean_of_z2 = 0.0;    ///< c, U
};

/// Coefficients for sample interval tau0_s > 0, sigma_unit >= 0, time_s > 0.
GaussMarkovStep gauss_markov_step(double sigma_unit, double time_s, double tau0_s);

}  // namespace imunoise::sim
