#pragma once
// Flicker rate noise as a fixed sum of first-order Gauss-Markov (AR1) terms: the GMWM term BGM
// (gmwm.hpp). A Kalman filter can carry Gauss-Markov states but not 1/f noise; the mixture is
// the flicker of one parameter B written in such states.
//
// Construction (from the exact sampled-series AR1 Allan variance gmwm_avar_ar1, no constant
// tuned to a record): correlation times T_i = (tau_lo / 1.8926) 10^(i / per_decade), from one
// decade below the span's shortest tau to the first grid point a decade above its longest
// (1.8926 T: the Allan peak of an AR1), and variance ratios w_i >= 0 by non-negative least squares on the relative misfit
//   sum_i w_i AVAR_AR1(T_i, m) / ((2 ln 2 / pi)) - 1
// at 8 averaging factors per octave over [m_lo, m_hi]. Terms whose ratio is 0 are dropped. With
// B = 1 the mixture's Allan variance is then the continuous flicker floor (2 ln 2 / pi) to the
// ripple reported (the largest relative deviation on that grid; 2 per decade: ~2.3 % at the
// shortest taus, below 1 % inside; 1 per decade: ~10 %). State i of a fit with flicker B has
// sigma_i = B sqrt(w_i) and correlation time T_i.
#include <cstddef>
#include <vector>

namespace imunoise::fit {

struct FlickerMixture {
  std::vector<double> correlation_time_s;  ///< ascending, only terms with w_i > 0
  std::vector<double> variance_per_b2;     ///< w_i = sigma_i^2 / B^2
  std::size_t m_lo = 0, m_hi = 0;          ///< averaging factors of the span it is flat over
  int per_decade = 0;
  double ripple = 0.0;  ///< max |AVAR / (2 ln 2 / pi) - 1| over the span (8 factors per octave)
  bool empty() const { return correlation_time_s.empty(); }
};

/// The mixture flat over averaging factors [m_lo, m_hi] (m_lo >= 1, m_hi >= m_lo) of sample
/// interval tau0_s, per_decade correlation times per decade (1..4). InputError otherwise.
FlickerMixture flicker_ar1_mixture(double tau0_s, std::size_t m_lo, std::size_t m_hi, int per_decade = 2);

/// Allan variance of the mixture at tau = m tau0 for B = 1 (sum of the exact AR1 forms).
double gmwm_avar_flicker_mixture(const FlickerMixture& mixture, double tau0_s, std::size_t m);

}  // namespace imunoise::fit
