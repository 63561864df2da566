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

/// The mtot/htot kernel (total.hpp) for `count` consecutive 3m-point subsequences of a sequence
/// u, given its prefix sums ul[i] = sum_{k<i} (u[k] - c - s k) for any c, s (a constant and a
/// linear trend in u leave the result unchanged; removing the local ones keeps ul small):
///   sum_{w<count} (1/(6 m^3)) sum_{j<6m} z_j(w)^2,
/// with z_j the third difference at stride m of the prefix of the 9m reflected sequence of the
/// half-average-detrended subsequence w. ul must hold count + 3m + 8 values (eight windows are
/// computed at once, one per lane; the lanes past count read the padding and are dropped).
/// O(m) per subsequence, no scratch memory.
long double reflected_window_sum(const double* ul, std::size_t m, std::size_t count);

}  // namespace imunoise::detail
