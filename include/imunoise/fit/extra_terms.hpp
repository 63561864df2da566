#pragma once
// Optional non-power-law terms of the noise model: first-order Gauss-Markov rate noise
// (sigma, correlation time T_c) and a sinusoid on the rate (amplitude A, frequency f0).
//
// Allan variance of each (SI, U = rate unit):
//   Gauss-Markov  sigma^2 * 2 g(x) / x^2,  x = tau / T_c,  g(x) = x - 3/2 + 2 e^-x - e^-2x / 2
//                 (sim/gauss_markov.hpp: a rate random walk for tau << T_c, white for tau >> T_c)
//   sinusoid      A^2 * (sin^2(pi f0 tau) / (pi f0 tau))^2
// Each is linear in its variance (sigma^2, A^2) once its nonlinear parameter (T_c, f0) is
// fixed, so the fit is a variable projection: for every trial T_c (f0) the power-law terms and
// the term's variance are solved by non-negative generalised least squares, and T_c (f0) is
// the minimiser of the resulting chi^2 (log grid, then golden-section refinement).
//
// Selection (is the term there?): the term is kept when adding it lowers chi^2 by more than
// the Bayesian information criterion's price of its two parameters (2 ln k for k taus), it
// dominates the fitted model at min_dominant_taus taus or more (the same data-sufficiency rule
// as the power-law terms), and its variance's interval excludes zero. Otherwise it is reported
// as not identified with an upper limit.
//
// Intervals: profile likelihood with the model covariance of the final fit held fixed: a value
// is inside when chi^2 minimised over every other parameter (T_c or f0 included) rises by at
// most the chi-squared(1) quantile of the level. When a term is kept, the power-law
// coefficients come from the joint fit and their intervals from the same profile. Coverage on
// simulated records: docs/fit.md and tests/fit/test_extra_terms.cpp.
//
// Weights: the covariance of the Allan variance estimates under the extended model, exact for
// the power-law and Gauss-Markov terms (CovarianceBasis with the term's T_c: EDF and the
// correlation between overlapping taus); a sinusoid is deterministic and only rescales each
// tau's variance by (model with it) / (model without it), which overstates it (conservative).
#include <string>

namespace imunoise::fit {

/// Allan variance of unit-variance Gauss-Markov rate noise with correlation time tc_s.
double gauss_markov_basis(double tc_s, double tau_s);
/// Allan variance of a unit-amplitude sinusoid of frequency f_hz: (sin^2(pi f tau)/(pi f tau))^2.
double sinusoid_basis(double f_hz, double tau_s);

/// How the test for one optional term went (reported beside its coefficients).
struct ExtraTermTest {
  bool requested = false;
  bool selected = false;         ///< kept in the model (identified)
  double delta_chi2 = 0.0;       ///< chi^2 without the term minus chi^2 with it
  double penalty = 0.0;          ///< what delta_chi2 had to exceed (BIC, 2 parameters)
  int dominant_taus = 0;         ///< taus where the term is the largest part of the model
  double tau_min_s = 0.0;        ///< range of those taus (0 0: none)
  double tau_max_s = 0.0;
  std::string verdict;           ///< one sentence: why kept or not
};

struct ExtraTermsReport {
  ExtraTermTest gauss_markov;
  ExtraTermTest sinusoid;
  /// True when a kept term changed the power-law coefficients (joint fit, profile intervals).
  bool joint = false;
  /// True when the terms were tried without being requested (FitOptions::auto_extra_terms)
  /// and at least one was kept; `reason` says why they were tried.
  bool automatic = false;
  std::string reason;
};

}  // namespace imunoise::fit
