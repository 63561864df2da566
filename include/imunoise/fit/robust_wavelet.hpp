#pragma once
// Robust Haar wavelet variance for the robust GMWM (Guerrier, Molinari, Victoria-Feser, "Robust
// inference for time series models: a wavelet-based framework", JASA 2014), written from the
// idea, not from the R gmwm package.
//
// The Haar MODWT coefficient at scale m is half the difference of adjacent window means of m
// samples; from the phase x (x_k = tau0 * sum of the first k rates):
//   W_t = (x_{t+2m} - 2 x_{t+m} + x_t) / (2 m tau0),   E[W^2] = nu^2(m) = AVAR(m) / 2.
// The classical estimate is the mean of W_t^2 (the overlapping Allan variance / 2). The robust
// one is an M-estimate of their scale s (they are centred at 0 for any stationary-increment
// noise) with Tukey's biweight
//   rho(u) = 1 - (1 - (u / c)^2)^3 for |u| <= c, 1 beyond;   mean_t rho(W_t / s) = delta,
// delta = E rho(Z) for Z standard normal (Fisher consistency: s^2 = nu^2 at the Gaussian). Each
// coefficient's influence is bounded (rho <= 1). Its asymptotic variance at the Gaussian for
// independent coefficients is s^2 E[(rho - delta)^2] / E[Z rho'(Z)]^2, against s^2 / 2 for the
// classical estimate: the efficiency e(c) = E[Z rho']^2 / (2 E[(rho - delta)^2]); c is chosen
// for a requested e (0.6 by default: c = 2.5...; breakdown point delta).
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::fit {

struct Biweight {
  double c = 0.0;           ///< tuning constant
  double delta = 0.0;       ///< E rho(Z): Fisher consistency at the Gaussian
  double efficiency = 0.0;  ///< e(c), Gaussian efficiency of the scale estimate
};

/// Gaussian efficiency of the biweight scale M-estimate with constant c (numerical quadrature).
double biweight_scale_efficiency(double c);

/// The biweight whose Gaussian efficiency is `efficiency` (in [0.3, 0.98]); InputError outside.
Biweight biweight_for_efficiency(double efficiency);

/// The M-estimate of s^2 of the zero-centred values x (no location), InputError when x is empty;
/// 0 when more than half of x is exactly 0.
double biweight_scale2(std::span<const double> x, const Biweight& b);

/// Robust Allan variance (2 x the robust Haar wavelet variance) at each averaging factor m
/// (2 m < phase.size()) of the phase samples phase_si (SI), spacing tau0_s.
std::vector<double> robust_avar(std::span<const double> phase_si, double tau0_s,
                                std::span<const std::size_t> m, const Biweight& b);

}  // namespace imunoise::fit
