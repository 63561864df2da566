#pragma once
// Inner loops of the difference estimators: sums of squared finite differences of phase at
// lag m over a contiguous run of start indices. Cloned for AVX2+FMA with a portable fallback
// chosen at load time, so one binary runs everywhere and uses the wide units where present.
#include <cstddef>

namespace imunoise::detail {

/// sum_{k<count} (x[k+2m] - 2 x[k+m] + x[k])^2
double sum_sq_second_difference(const double* x, std::size_t m, std::size_t count);

/// sum_{k<count} (x[k+3m] - 3 x[k+2m] + 3 x[k+m] - x[k])^2
double sum_sq_third_difference(const double* x, std::size_t m, std::size_t count);

}  // namespace imunoise::detail
