#pragma once
// The total family: totdev, mtotdev, ttotdev, htotdev (NIST SP 1065, sec. 5.2.11-5.2.14;
// D. A. Howe and C. A. Greenhall on TOTVAR). Each extends the data by reflection so that every
// averaging factor uses all the data, which lowers the variance of the long-tau estimates.
//
// Input: N angle (phase) samples x[0..N-1] spaced tau0 apart; tau = m tau0.
//
// totdev: x is extended at both ends by inverted reflection, x*[-j] = 2 x[0] - x[j] and
//   x*[N-1+j] = 2 x[N-1] - x[N-1-j] (j = 1..N-2), and
//     Totvar(tau) = 1 / (2 tau^2 (N-2)) sum_{i=1}^{N-2} (x*[i-m] - 2 x*[i] + x*[i+m])^2.
//   Domain 1 <= m <= floor((N-1)/2); n = N - 2. m = 1 equals oadev at m = 1.
//   Cost: O(N) per factor (one pass over the 3N-point extension), factors spread over threads.
//
// mtotdev: for each n = 0..N-3m, the 3m-point phase subsequence x[n..n+3m-1] has its frequency
//   offset removed by the half-average method (slope = (mean of the last h points - mean of the
//   first h points) / (3m - h), h = floor(3m/2): exact for a linear phase, so a constant rate
//   never matters), is extended at both ends by uninverted (even) reflection to 9m points e, and
//     Mtot(n) = 1/(6m) sum_{j=0}^{6m-1} z_j^2,  z_j = (1/m) sum_{k=j}^{j+m-1} (e[k+2m] - 2 e[k+m] + e[k])
//     Mod Totvar(tau) = 1 / (2 tau^2 (N-3m+1)) sum_n Mtot(n).
//   Domain 1 <= m <= floor(N/3); n = N - 3m + 1 (Stable32's count). ttotdev = tau/sqrt(3) mtotdev.
//   Algorithm: per subsequence, a prefix sum P of the detrended points; the prefix of the
//   reflected 9m sequence is an odd extension of P about each fold, so the six z_{r+km}
//   (k = 0..5) are fixed combinations of P at six points: O(m) per subsequence, O(N m) per
//   factor (AllanTools and the SP 1065 definition are O(N m^2)), eight subsequences per vector
//   (src/core/kernels.cpp). No sub-O(N m) exact algorithm is known to us (SP 1065, the
//   TOTVAR papers and Stable32's notes give none); the subsequences are spread over threads.
//
// htotdev: the same construction applied to the N-1 rate (frequency) values y[k] = (x[k+1] -
//   x[k]) / tau0, whose linear drift is removed by the half-average method before the even
//   reflection; z_j is then the second difference of m-averages of y (a third difference of
//   phase) and
//     Htotvar(tau) = 1 / (6 (N-3m)) sum_{n=0}^{N-1-3m} Mtot_y(n),
//   with n = N - 3m subsequences (Stable32's count). At m = 1 Stable32 reports the overlapping
//   Hadamard deviation; so does htotdev. Domain 1 <= m <= floor((N-1)/3). Cost as mtotdev.
//   No bias correction is applied here; htotdev_bias_factor() gives SP 1065's.
//
// Accuracy: agreement with the literal SP 1065 definitions (tests/core/reference_total.hpp) to
// better than 1e-10 relative on random data with an offset 1e6 times the noise; NBS14 and
// Stable32 PHASE.DAT values to their printed precision (tests/core/test_total.cpp).
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

std::vector<DevPoint> totdev(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options = {});

/// totdev over the whole range the reflection supports, 1 <= m <= N-1 (AllanTools' range;
/// totdev() keeps Stable32's m <= floor((N-1)/2)). Same formula, n = N - 2 at every m. Beyond
/// N/2 the estimate leans mostly on reflected points: use it for compatibility, not for
/// inference. Throws InputError for m outside 1..N-1 or N < 3.
std::vector<DevPoint> totdev_reflected_range(std::span<const double> phase, double tau0_s,
                                             std::span<const std::size_t> factors,
                                             const DevOptions& options = {});

std::vector<DevPoint> mtotdev(std::span<const double> phase, double tau0_s,
                              std::span<const std::size_t> factors, const DevOptions& options = {});

/// Time total deviation tau/sqrt(3) * mtotdev, in the angle unit.
std::vector<DevPoint> ttotdev(std::span<const double> phase, double tau0_s,
                              std::span<const std::size_t> factors, const DevOptions& options = {});

std::vector<DevPoint> htotdev(std::span<const double> phase, double tau0_s,
                              std::span<const std::size_t> factors, const DevOptions& options = {});

/// The documented bias of the total family and Theo1 under power-law noise alpha, as the factor
/// that multiplies the raw *variance* to give the bias-corrected (Allan / Hadamard equivalent)
/// value; NaN where no correction is defined (then report the raw value). m averaging factor,
/// n_phase phase points.
///   totdev:  Totvar = Avar (1 - a tau/T): factor 1/(1 - a m/N), a = 0 (alpha 0),
///            1/(3 ln 2) (-1), 0.75 (-2) (Howe, "Total variance explained", 1999, Table 1);
///            1 for the PM noises.
///   mtotdev, ttotdev: Mtot/Mvar = 0.94, 0.83, 0.73, 0.70, 0.69 for alpha 2..-2 (Riley, "CI2",
///            MTOT bias table): factor 1/ratio. Stable32 does not apply it (its rows are raw).
///   htotdev: Htot = Hvar (1 + a), a = -0.005, -0.149, -0.229, -0.283, -0.321 for alpha 0..-4
///            (Howe et al., PTTI 2000): factor 1/(1 + a); none at m = 1 (ohdev) and for PM noise.
///            Reproduces Stable32's bias-corrected PHASE.DAT row (alpha 0, AF 2) to 5 digits.
///   theo1:   Avar/Theo1 = a + b / (0.75 m)^c (Howe et al., EFTF 2004, Table 1): alpha 2:
///            (0.09, 0.74, 0.40), 1: (0.14, 0.82, 0.30), 0: (1, 0, 0), -1: (1.87, -1.05, 0.79),
///            -2: (2.70, -1.53, 0.85). Stable32 1.60's bias-corrected PHASE.DAT row (alpha 1,
///            AF 10) is 1.2% above this (not resolved; see docs/estimators.md).
double bias_variance_factor(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase);

/// Multiplies dev, ci_low and ci_high of every point whose alpha is set (fill_confidence) by
/// sqrt(bias_variance_factor); points without a defined correction keep their raw values.
/// Returns how many points were corrected.
std::size_t apply_bias_correction(std::vector<DevPoint>& points, Estimator estimator,
                                  std::size_t n_phase);

}  // namespace imunoise
