#pragma once
// Sums of squared phase differences, the common core of every estimator in allan.hpp,
// modified_allan.hpp and hadamard.hpp. Each returns, per averaging factor, the sum and the
// number of terms; the caller scales them into a variance.
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::detail {

struct DifferenceSums {
  std::vector<double> sum_sq;     ///< per factor: sum of squared differences (phase unit^2)
  std::vector<std::size_t> n;     ///< per factor: number of terms
};

/// Overlapping sums, start index k = 0, 1, 2, ...: sum_k (Delta^order_m x[k])^2 for order 2
/// (Allan) or 3 (Hadamard). All factors are fused into one pass over cache-sized blocks.
DifferenceSums overlapping_difference_sums(std::span<const double> phase, int order,
                                           std::span<const std::size_t> factors, unsigned threads);

/// Non-overlapping sums, start index k = 0, m, 2m, ...
DifferenceSums strided_difference_sums(std::span<const double> phase, int order,
                                       std::span<const std::size_t> factors);

/// Modified-Allan sums: sum_j (sum_{i=j}^{j+m-1} Delta^2_m x[i])^2, j = 0 .. N-3m.
DifferenceSums modified_difference_sums(std::span<const double> phase,
                                        std::span<const std::size_t> factors, unsigned threads);

}  // namespace imunoise::detail
