#pragma once
// The optional Gauss-Markov and sinusoid terms on top of a finished power-law fit (see
// include/imunoise/fit/extra_terms.hpp). Internal to the fit module.
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/fit/fit.hpp"

namespace imunoise::fit::detail {

/// The curve the power-law fit used (taus with positive variance, SI).
struct CurveView {
  std::span<const std::size_t> m;
  std::span<const double> tau_s;
  std::span<const double> avar;
};

/// Starting values of the nonlinear parameters for the multi-start search (besides the grid):
/// taus where the curve shows a bump (a concave bend, the largest excess over the power-law
/// model). A Gauss-Markov term's sigma^2 peaks near tau = 1.89 T_c, a sinusoid's near
/// tau = 0.371 / f0, so each bump tau gives T_c = tau / 1.89 and f0 = 0.371 / tau.
struct BumpStarts {
  std::vector<double> tau_s;
};

/// Tests the terms requested in options (gauss_markov, sinusoid) against result's power-law
/// model, fills result.extras and result.coefficients.gauss_markov / .sinusoid, and when a term
/// is kept replaces the power-law coefficients, residuals and diagnostics by the joint fit's.
/// When options.model_mismatch is set and chi^2 rejects a candidate model, its weights carry a
/// mismatch scatter as in the power-law fit (Paule-Mandel, variance capped at the data).
/// `starts` (may be null) adds starting points to the search of the two-term model.
/// automatic (FitOptions::auto_extra_terms, the power laws already rejected): the search starts
/// with the power-law fit's mismatch scatter in the weights, and a term (optional or power-law)
/// also counts as supported when it adds more than 2 sd to the model at min_dominant taus.
/// Requested terms keep the stricter rules they were validated with (docs/fit.md).
void fit_extra_terms(const CurveView& curve, std::size_t n_phase, double tau0_s,
                     const FitOptions& options, FitResult& result,
                     const BumpStarts* starts = nullptr, bool automatic = false);

}  // namespace imunoise::fit::detail
