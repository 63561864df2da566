#pragma once
// Theory beside simulation: the Allan variance and the PSD of any noise model.
//
// Three independent routes, which tests/sim/theory_test.cpp checks against one another:
//  1. Closed forms per term, summed (IEEE Std 952-1997 Annex C; El-Sheimy et al. 2008):
//       Q: 3 Q^2 / tau^2            N: N^2 / tau           K: K^2 tau / 3
//       R: R^2 tau^2 / 2            B: the Gauss-Markov bank of flicker.hpp (exact for what is
//       simulated; equal to (2 ln 2 / pi) B^2 within 2e-3 over the flicker range), or the ideal
//       floor (2 ln 2 / pi) B^2 for nominal_allan_variance
//       Gauss-Markov: gauss_markov.hpp    sinusoid A, f0: A^2 (sin^2(pi f0 tau) / (pi f0 tau))^2
//  2. The paper's eq. 4, sigma^2(tau) = 4 int_0^inf S(f) sin^4(pi f tau) / (pi f tau)^2 df,
//     integrated numerically from the two-sided PSD S(f) below (relative accuracy ~1e-10).
//  3. Simulation (generator.hpp), whose overlapping Allan deviation lies within its
//     chi-squared band around route 1.
// Routes 1 and 2 agree to 1e-6 relative (tested) wherever both exist: the rate ramp's PSD
// R^2 / (2 pi f)^3 is not integrable at f -> 0, so eq. 4 does not exist for R (the closed form
// does); the sinusoid's spectrum is a line of power A^2/2 at f0, integrated exactly.
//
// PSDs are two-sided, in U^2/Hz (N^2 for white noise, as in IEEE 952 and the paper):
//   Q: (2 pi f)^2 tau0 Q^2 for f <= 1/(2 tau0), 0 above (quantization is band-limited by the
//      sampling; with it eq. 4 gives exactly 3 Q^2 / tau^2 at tau = m tau0)
//   N: N^2     B: B^2 / (2 pi f) (ideal) or the bank's sum of Lorentzians     K: K^2 / (2 pi f)^2
//   Gauss-Markov: 2 sigma^2 T / (1 + (2 pi f T)^2)     R: R^2 / (2 pi f)^3 (formal)
// Output-stage effects (saturation, ADC) are not part of the theory; a scale factor s scales
// variances by s^2.
#include "imunoise/sim/noise_model.hpp"

namespace imunoise::sim {

/// The Allan variance of each term at one tau (U^2).
struct AllanTerms {
  double q = 0.0, n = 0.0, b = 0.0, k = 0.0, r = 0.0, gm = 0.0, sine = 0.0;
  double total() const { return q + n + b + k + r + gm + sine; }
};

/// Which flicker spectrum to use: the generator's Gauss-Markov bank, or ideal 1/f.
enum class FlickerForm { bank, ideal };

/// Closed forms at tau_s > 0. With FlickerForm::bank (exactly what the generator simulates)
/// a model with b_unit > 0 needs its flicker range set (resolve_flicker_range); otherwise
/// InputError.
AllanTerms allan_variance_terms(const NoiseModel& model, double tau_s,
                                FlickerForm flicker = FlickerForm::bank);

/// Sum of allan_variance_terms (U^2).
double allan_variance(const NoiseModel& model, double tau_s, FlickerForm flicker = FlickerForm::bank);

/// The paper's eq. 5 (with the Gauss-Markov and sinusoid terms): flicker as its ideal floor.
inline double nominal_allan_variance(const NoiseModel& model, double tau_s) {
  return allan_variance(model, tau_s, FlickerForm::ideal);
}

/// Two-sided PSD of the rate (U^2/Hz) at f_hz > 0 for sample interval tau0_s (which band-limits
/// Q). The sinusoid's line and the bias (a line at f = 0) are not included.
double psd(const NoiseModel& model, double tau0_s, double f_hz,
           FlickerForm flicker = FlickerForm::bank);

/// The paper's eq. 4 evaluated numerically from psd() plus the sinusoid's line, at tau_s > 0.
/// Throws InputError when r_unit_per_s != 0 (eq. 4 diverges for a rate ramp).
/// Quadrature: Gauss-Legendre (20 points) on octaves of x = pi f tau below pi, on each period
/// of sin^4 up to x = 256 pi, on octaves above with the oscillating part of the tail taken by
/// two terms of its asymptotic expansion; the band edge of Q is a breakpoint.
double allan_variance_eq4(const NoiseModel& model, double tau0_s, double tau_s,
                          FlickerForm flicker = FlickerForm::bank);

}  // namespace imunoise::sim
