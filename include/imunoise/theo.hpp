#pragma once
// Theo1 deviation (D. A. Howe and T. K. Peppler; NIST SP 1065 sec. 5.2.15), with Stable32's
// conventions: tau = 0.75 m tau0 and even averaging factors m only.
//
// Input: N angle (phase) samples x[0..N-1] spaced tau0 apart; m even, k = m/2:
//   Theo1(m) = 1 / (0.75 (N-m) (m tau0)^2) *
//              sum_{i=0}^{N-m-1} sum_{d=0}^{k-1} (x[i] - x[i+k-d] + x[i+m] - x[i+k+d])^2 / (k-d)
//   DevPoint.tau_s = 0.75 m tau0; DevPoint.n = (N-m) k terms (Stable32's count).
// Domain: m even, 2 <= m <= N-1. No bias correction is applied (Stable32's "alpha = 0" row);
// the noise-dependent correction (TheoBR / Stable32's bias-corrected rows) is not provided yet.
//
// Algorithm: for each d, one contiguous pass over i of four phase streams (vectorized; an AVX2
// clone is chosen at run time when the CPU has it), the d's spread over threads. O(N m) per
// factor, the cost of the definition itself: the exact Theo1 has no faster formulation known to
// us. Taylor & Howe's "Fast TheoBR" (IEEE UFFC 2010) reaches O(N log N) by evaluating Theo1 on
// phase decimated by averaging, which is an approximation of a different statistic; it is not
// used here, so that theo1 stays the exact SP 1065 quantity.
// Accuracy: agrees with the literal double sum (tests/core/reference_total.hpp) to 1e-12
// relative on random data with a large offset; Stable32's PHASE.DAT value to its 5 digits.
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise {

std::vector<DevPoint> theo1(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options = {});

/// The averaging factors of a tau grid for `estimator` over n_phase phase points, in its domain.
/// For theo1 the grid is laid out in tau = 0.75 m tau0: octave gives m = 2, 4, 8, ...
/// (tau = 1.5, 3, 6, ... tau0), decade m = 2, 4 and 10, 20, 40 x 10^k (even m only), all every
/// even m, perdecade:K the even m nearest K log-spaced values, and explicit taus must equal
/// 0.75 m / rate_hz for an even m. Every other estimator uses averaging_factors() unchanged.
std::vector<std::size_t> estimator_averaging_factors(Estimator estimator, const TauGrid& grid,
                                                     double rate_hz, std::size_t n_phase);

}  // namespace imunoise
