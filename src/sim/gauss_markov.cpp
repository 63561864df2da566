#include "deterministic_fp.hpp"  // first: no fused multiply-add in this file

#include "imunoise/sim/gauss_markov.hpp"

#include <cmath>
#include <numbers>

#include "imunoise/sim/portable_math.hpp"

namespace imunoise::sim {

double gauss_markov_g(double x) {
  if (x < 1.0) {
    // g(x) = sum_{n>=3} (-1)^n (2 - 2^(n-1)) x^n / n!; the terms fall below 1e-20 of the sum
    // by n = 30 for x < 1 and the largest term is < 10 times the sum.
    double term = x * x * x / 6.0;  // x^n / n! for n = 3
    double sum = 0.0;
    double sign = -1.0;             // (-1)^3
    double pow2 = 4.0;              // 2^(n-1)
    for (int n = 3; n <= 30; ++n) {
      sum += sign * (2.0 - pow2) * term;
      term = term * x / static_cast<double>(n + 1);
      sign = -sign;
      pow2 *= 2.0;
    }
    return sum;
  }
  const double e1 = portable::exp(-x);
  return (x - 1.5) + (2.0 * e1 - 0.5 * (e1 * e1));
}

double gauss_markov_allan_variance(double sigma_unit, double time_s, double tau_s) {
  if (sigma_unit == 0.0) return 0.0;
  const double x = tau_s / time_s;
  return 2.0 * sigma_unit * sigma_unit * gauss_markov_g(x) / (x * x);
}

double gauss_markov_psd(double sigma_unit, double time_s, double f_hz) {
  const double w = 2.0 * std::numbers::pi * f_hz * time_s;
  return 2.0 * sigma_unit * sigma_unit * time_s / (1.0 + w * w);
}

GaussMarkovStep gauss_markov_step(double sigma_unit, double time_s, double tau0_s) {
  const double x = tau0_s / time_s;
  const double e1 = -portable::expm1(-x);  // 1 - phi, accurate when x is tiny
  const double one_minus_phi2 = e1 * (2.0 - e1);
  GaussMarkovStep step;
  step.phi = 1.0 - e1;
  step.state_noise = sigma_unit * std::sqrt(one_minus_phi2);
  step.mean_of_state = e1 / x;
  step.mean_of_z1 = sigma_unit * (e1 * e1) / (x * std::sqrt(one_minus_phi2));
  // Both terms are ~x^3 for small x (x^3/6 remains); g's series keeps them accurate.
  const double residual = 2.0 * gauss_markov_g(x) - (e1 * e1 * e1) / (2.0 - e1);
  step.mean_of_z2 = residual > 0.0 ? (sigma_unit / x) * std::sqrt(residual) : 0.0;
  return step;
}

}  // namespace imunoise::sim
