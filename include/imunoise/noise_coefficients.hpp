#pragma once
// The identified noise model of one sensor axis: what `fit` produces and what the datasheet
// comparison, the navigation models and the filter exports consume.
//
// Values are SI in the rate's quantity: for a gyro the rate unit is rad/s, so Q is in rad,
// N in rad/sqrt(s), B in rad/s, K in rad/s/sqrt(s), R in rad/s^2; for an accelerometer replace
// rad by m/s. Conversion to the input's unit and to customary units happens at the edges
// (units.hpp). The allan variance of the model is (paper eq. 5, IEEE 952 Annex C)
//   sigma^2(tau) = 3 Q^2/tau^2 + N^2/tau + (2 ln 2/pi) B^2 + K^2 tau/3 + R^2 tau^2/2
//                  (+ Gauss-Markov and sinusoid terms when present).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/units.hpp"

namespace imunoise {

/// One coefficient with its two-sided confidence interval.
struct Coefficient {
  double value = 0.0;  ///< best estimate (SI); 0 when not identified
  double ci_low = std::numeric_limits<double>::quiet_NaN();   ///< lower bound (SI)
  double ci_high = std::numeric_limits<double>::quiet_NaN();  ///< upper bound (SI)
  bool identified = false;  ///< false: the record cannot support this term (value is 0)
  std::string note;         ///< why not identified, or a warning; empty otherwise
};

/// First-order Gauss-Markov rate noise: sigma (rate, SI) and correlation time (s).
struct GaussMarkovTerm {
  Coefficient sigma;
  Coefficient correlation_time_s;
};

/// Sinusoidal rate noise: amplitude (rate, SI) and frequency (Hz).
struct SinusoidTerm {
  Coefficient amplitude;
  Coefficient frequency_hz;
};

/// True when the term's sigma and correlation time were both identified (positive, finite).
inline bool identified(const GaussMarkovTerm& g) {
  return g.sigma.identified && g.correlation_time_s.identified && g.sigma.value > 0.0 &&
         g.correlation_time_s.value > 0.0;
}

struct NoiseCoefficients {
  Quantity quantity = Quantity::angular_rate;  ///< angular_rate (gyro) or acceleration (accel)
  double confidence_level = 0.95;              ///< level of every ci_low/ci_high
  Coefficient quantization;        ///< Q: angle (rad) / velocity (m/s)
  Coefficient random_walk;         ///< N: rad/sqrt(s) (ARW) / m/s/sqrt(s) (VRW)
  Coefficient bias_instability;    ///< B: rad/s / m/s^2
  Coefficient rate_random_walk;    ///< K: rad/s/sqrt(s) / m/s^2/sqrt(s)
  Coefficient rate_ramp;           ///< R: rad/s^2 / m/s^3
  /// Every first-order Gauss-Markov term of the model, ordered by correlation time (the wls
  /// fit has at most one, gmwm any number; empty: none fitted). A term reported but not
  /// identified (the wls test rejected it) stays in the list with identified = false.
  std::vector<GaussMarkovTerm> gauss_markov;
  std::optional<SinusoidTerm> sinusoid;
};

}  // namespace imunoise
