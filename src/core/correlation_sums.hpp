#pragma once
// Overlapping sums of squared second or third phase differences for many factors at once,
// through correlations computed by FFT instead of one pass over the record per factor.
//
// Expanding (sum_a c_a x[k + a m])^2 and summing over the starts k gives squares (prefix sums)
// and, for each pair a < b, the correlation at lag (b - a) m restricted to the starts' range:
// the full autocorrelation (one FFT) minus a head and a tail, which are "wedge" correlations
// sum_{p < alpha m} u[p] v[p + beta m] over every m at once (a dyadic recursion of FFTs,
// O(N log^2 N)). Cancellation makes this inexact where the difference sums are small against
// the phase's energy (small m, few starts, or a phase dominated by random walk of the rate):
// each factor comes with a rounding bound, and the caller sums directly the ones it rejects.
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::detail {

struct CorrelationSums {
  std::vector<double> sum_sq;          ///< per factor: sum of squared differences (phase unit^2)
  std::vector<double> relative_bound;  ///< per factor: bound on |rounding| / sum_sq (inf: unusable)
};

/// Sums for `factors` (each with order * m < phase.size()); order 2 (Allan) or 3 (Hadamard).
/// `input_rounding`: how far each phase value may already be from the exact one (0 for data as
/// given). Bitwise identical for any thread count.
CorrelationSums correlation_difference_sums(std::span<const double> phase, int order,
                                            std::span<const std::size_t> factors, unsigned threads,
                                            double input_rounding = 0.0);

/// The phase minus its least-squares polynomial of `degree` 0, 1 or 2 (fitted in long double;
/// each value rounded once).
std::vector<double> detrended_phase(std::span<const double> phase, int degree);

/// The transforms' rounding of one sum, against the detrended phase's energy sum y^2:
/// |error| <= kCorrelationRounding * eps * (sum |c_a|)^2 * sum y^2. Measured: the largest
/// ratio of error to eps (sum |c_a|)^2 sum y^2 over white and random-walk phase and rate, 1e5
/// and 1e6 samples, orders 2 and 3 (against long-double direct sums) was 1.25; 16 keeps a
/// factor of 13 (docs/performance.md).
inline constexpr double kCorrelationRounding = 16.0;

}  // namespace imunoise::detail
