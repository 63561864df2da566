#pragma once
// Bias instability: flicker (1/f) rate noise realised as a documented bank of Gauss-Markov
// processes.
//
// Target: two-sided rate PSD B^2 / (2 pi f), whose Allan deviation is the constant floor
// sqrt(2 ln 2 / pi) B = 0.6642825 B at every tau (IEEE 952 Annex C).
//
// Method. Pure 1/f noise is not stationary and has no finite-state realisation; over a stated
// tau range [tau_min, tau_max] it is reproduced by a sum of independent first-order
// Gauss-Markov processes (gauss_markov.hpp) with geometrically spaced correlation times
// T_i = T_lo r^i, r = 10^(1/1.5) (1.5 poles per decade), each of variance B^2 ln(r) / pi, whose
// PSDs add up to B^2 / (2 pi f) between the poles, plus two end corrections:
//   - low end: white rate noise of PSD 2 sigma^2 T_lo / (r - 1), the low-frequency level of
//     the infinitely many faster poles left out (they act as white noise at tau >> T_lo);
//   - high end: the slowest pole's variance is multiplied by r / (r - 1), which stands in, to
//     first order, for the slower poles left out (they act as a rate random walk at tau << T).
// T_lo = tau_min / 16 and the slowest pole is at least 8 tau_max.
//
// Accuracy (the bank is exactly what the generator simulates, so this is a property of the
// closed form sum, checked densely in tests/sim/flicker_test.cpp for many ranges):
//   | sigma_bank(tau) / (0.6642825 B) - 1 | <= 1e-3  for tau_min <= tau <= tau_max,
// with a ripple of +-6e-4 between poles. Below tau_min the deviation rises (white-like), above
// tau_max it falls (white-like beyond the slowest pole). The range may span at most
// kFlickerMaxDecades decades; its lower end must be at least one sample interval (checked by
// check_sampling). Cost: about 1.5 normal variates per sample per decade of range, plus 1.
#include <vector>

namespace imunoise::sim {

inline constexpr double kFlickerPolesPerDecade = 1.5;
/// Guaranteed relative accuracy of the Allan deviation floor over the stated range.
inline constexpr double kFlickerFloorTolerance = 1e-3;
/// Widest range the generator honours: tau_max / tau_min <= 10^kFlickerMaxDecades.
inline constexpr double kFlickerMaxDecades = 12.0;
/// Margins: fastest pole at tau_min / kFlickerLowMargin, slowest at >= tau_max * kFlickerHighMargin.
inline constexpr double kFlickerLowMargin = 16.0;
inline constexpr double kFlickerHighMargin = 8.0;

/// sqrt(2 ln 2 / pi) = 0.66428247026796...: Allan floor per unit B.
inline constexpr double kFlickerFloorPerB = 0.66428247026796002;

struct GaussMarkovPole {
  double sigma_unit = 0.0;  ///< stationary standard deviation, U
  double time_s = 0.0;      ///< correlation time, s
};

struct FlickerBank {
  std::vector<GaussMarkovPole> poles;  ///< ascending correlation times
  double white_n_unit_sqrt_s = 0.0;    ///< low-end correction: white rate noise, U*sqrt(s)
  double tau_min_s = 0.0;              ///< honoured range
  double tau_max_s = 0.0;
};

/// The bank for bias instability b_unit (U) over [tau_min_s, tau_max_s]. Throws InputError if
/// b_unit is negative or not finite, or the range is empty, not finite or wider than
/// kFlickerMaxDecades. b_unit = 0 gives a bank with no poles.
FlickerBank design_flicker_bank(double b_unit, double tau_min_s, double tau_max_s);

/// Exact Allan variance (U^2) of the bank at tau_s (sum of Gauss-Markov closed forms + white).
double flicker_bank_allan_variance(const FlickerBank& bank, double tau_s);

/// Exact two-sided PSD (U^2/Hz) of the bank at f_hz > 0.
double flicker_bank_psd(const FlickerBank& bank, double f_hz);

}  // namespace imunoise::sim
