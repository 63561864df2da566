#pragma once
// Internal: the continuous-time power-law model of Greenhall & Riley (PTTI 2003), shared by the
// EDF algorithm (edf.cpp) and the R(n) noise identification (noise_id.cpp).
namespace imunoise::detail {

/// Autocovariance at lag t (units of tau) of z, the d-th difference (lag tau) of phase that is
/// F times the first difference of w over tau/F (F = m: tau0-sampled phase; F = 1: phase
/// averaged over tau; F = infinity: point samples, alpha <= 0 only), for power-law FM noise
/// alpha in -4..2 (paper eqs. 7-9).
double power_law_sz(double t, double F, int alpha, int d);

}  // namespace imunoise::detail
