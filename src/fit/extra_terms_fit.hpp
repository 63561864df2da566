#pragma once
// The optional Gauss-Markov and sinusoid terms on top of a finished power-law fit (see
// include/imunoise/fit/extra_terms.hpp). Internal to the fit module.
#include <cstddef>
#include <span>

#include "imunoise/fit/fit.hpp"

namespace imunoise::fit::detail {

/// The curve the power-law fit used (taus with positive variance, SI).
struct CurveView {
  std::span<const std::size_t> m;
  std::span<const double> tau_s;
  std::span<const double> avar;
};

/// Tests the terms requested in options (gauss_markov, sinusoid) against result's power-law
/// model, fills result.extras and result.coefficients.gauss_markov / .sinusoid, and when a term
/// is kept replaces the power-law coefficients, residuals and diagnostics by the joint fit's.
void fit_extra_terms(const CurveView& curve, std::size_t n_phase, double tau0_s,
                     const FitOptions& options, FitResult& result);

}  // namespace imunoise::fit::detail
