#pragma once
// Theo1 deviation (D. A. Howe and T. K. Peppler; NIST SP 1065 sec. 5.2.15), with Stable32's
// conventions: tau = 0.75 m tau0 and even averaging factors m only.
//
// Input: N angle (phase) samples x[0..N-1] spaced tau0 apart; m even, k = m/2:
//   Theo1(m) = 1 / (0.75 (N-m) (m tau0)^2) *
//              sum_{i=0}^{N-m-1} sum_{d=0}^{k-1} (x[i] - x[i+k-d] + x[i+m] - x[i+k+d])^2 / (k-d)
//   DevPoint.tau_s = 0.75 m tau0; DevPoint.n = (N-m) k terms (Stable32's count).
// Domain: m even, 2 <= m <= N-1. No bias correction is applied (Stable32's "alpha = 0" row).
//
// ThêoBR (theobr; Howe & Tasset, EFTF 2004; Howe, Taylor & Tassett, FCS 2006; Taylor & Howe,
// UFFC 2010): Theo1 scaled by the record's own Avar/Theo1 ratio, so that no noise type has to be
// assumed:
//   ThêoBR(m) = kf Theo1(m),  kf = 1/(n+1) sum_{i=0}^{n} Avar(9 + 3i) / Theo1(12 + 4i),
//   Avar the overlapping Allan variance (same tau: 0.75 (12 + 4i) = 9 + 3i), and
//   n = floor(N/30) - 3 (TheoBrRatios::taylor_howe, the default: Avar only out to a tenth of
//       the record, where it is reliable), or
//   n = floor(N/6) - 3 (TheoBrRatios::stable32: Stable32's Run/Plot "Auto/BR"; it reproduces
//       Stable32's bias-corrected Theo1 row on PHASE.DAT, 8.3520e-02 at m = 10, kf = 0.6028,
//       but the Avar ratios out to N/2 rest on a handful of terms and pull kf down: on the same
//       white-FM record the taylor_howe kf is 1.086, the first 20 ratios average 0.997).
//   Ratios whose Avar has no term (9 + 3i > (N-1)/2) are left out.
// Domain: N >= 90 (n >= 0 for taylor_howe), m as Theo1.
// Cost: kf needs Theo1 at n + 1 factors up to 4n + 12: about 0.0011 N^3 terms for
// taylor_howe (measured on two cores: 0.24 s at N = 1e4, 3.5 s at 3e4; about 2.4 min at 1e5)
// and 0.015 N^3 for stable32 (2.3 s at 1e4). The sums are exact; no decimation is used.
//
// Algorithm: for each d, one contiguous pass over i of four phase streams (vectorized; an AVX2
// clone is chosen at run time when the CPU has it), the d's spread over threads. O(N m) per
// factor, the cost of the definition itself. Lewis (IEEE UFFC 2020) computes Theo1 at every
// even m in O(N^2) in all from running lag products of the phase; that would make ThêoBR's kf
// O(N^2), but the expanded products carry an error of about eps |x|^2 / (increment at lag m)^2
// relative, (N/m)^3 eps for random-walk FM (an estimate, not measured), so it is not used.
// Accuracy: agrees with the literal double sum (tests/core/reference_total.hpp) to 1e-12
// relative on random data with a large offset; Stable32's PHASE.DAT value to its 5 digits.
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise {

std::vector<DevPoint> theo1(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options = {});

/// ThêoBR's bias factor kf = mean Avar(9 + 3i) / Theo1(12 + 4i) and how many ratios it averages.
struct TheoBiasFactor {
  double avar_over_theo1 = 1.0;
  std::size_t ratios = 0;
};

/// How many Avar/Theo1 ratios kf averages (see above).
enum class TheoBrRatios { taylor_howe, stable32 };

/// Parses "taylor-howe" or "stable32"; throws InputError otherwise.
TheoBrRatios parse_theobr_ratios(std::string_view name);

/// Number of Avar/Theo1 ratios kf averages over n_phase points (0: too short for ThêoBR).
std::size_t theobr_ratio_count(std::size_t n_phase, TheoBrRatios ratios);

/// kf of the record (see above); throws InputError for fewer than 90 phase points.
TheoBiasFactor theobr_bias_factor(std::span<const double> phase, double tau0_s,
                                  const DevOptions& options = {},
                                  TheoBrRatios ratios = TheoBrRatios::taylor_howe);

/// ThêoBR deviations sqrt(kf) Theo1(m); kf is computed once and, if bias_factor is given,
/// returned through it.
std::vector<DevPoint> theobr(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options = {},
                             TheoBrRatios ratios = TheoBrRatios::taylor_howe,
                             TheoBiasFactor* bias_factor = nullptr);

/// Number of Theo1 terms ((N - m) m / 2 summed over the 12 + 4i) that kf costs: the CLI's
/// time budget uses it.
double theobr_bias_factor_terms(std::size_t n_phase, TheoBrRatios ratios = TheoBrRatios::taylor_howe);

/// The averaging factors of a tau grid for `estimator` over n_phase phase points, in its domain.
/// For theo1 the grid is laid out in tau = 0.75 m tau0: octave gives m = 2, 4, 8, ...
/// (tau = 1.5, 3, 6, ... tau0), decade m = 2, 4 and 10, 20, 40 x 10^k (even m only), all every
/// even m, perdecade:K the even m nearest K log-spaced values, and explicit taus must equal
/// 0.75 m / rate_hz for an even m. Every other estimator uses averaging_factors() unchanged.
std::vector<std::size_t> estimator_averaging_factors(Estimator estimator, const TauGrid& grid,
                                                     double rate_hz, std::size_t n_phase);

}  // namespace imunoise
