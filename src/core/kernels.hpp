#pragma once
// Inner loops of the difference estimators: sums of squared finite differences of phase at
// lag m over a contiguous run of start indices. Cloned for AVX2+FMA with a portable fallback
// chosen at load time, so one binary runs everywhere and uses the wide units where present.
#include <cmath>
#include <cstddef>

namespace imunoise::detail {

/// Neumaier's compensated addition: sum + compensation carries the exact running total to
/// about one ulp, so an integral stays correct over 1e9 samples. Always inlined: the clones
/// in kernels.cpp must inline every callee.
__attribute__((always_inline)) inline void neumaier_add(double& sum, double& compensation, double value) {
  const double t = sum + value;
  if (std::abs(sum) >= std::abs(value)) {
    compensation += (sum - t) + value;
  } else {
    compensation += (value - t) + sum;
  }
  sum = t;
}

/// sum_{k<count} (x[k+2m] - 2 x[k+m] + x[k])^2
double sum_sq_second_difference(const double* x, std::size_t m, std::size_t count);

/// sum_{k<count} (x[k+3m] - 3 x[k+2m] + 3 x[k+m] - x[k])^2
double sum_sq_third_difference(const double* x, std::size_t m, std::size_t count);

/// Consecutive factors share their windows: the terms of factors m, m+1, ..., m+7 at the same
/// starts read x[k + s (m + j)], shifts of one another. The sums of sum_sq_second_difference
/// (Order 2) or sum_sq_third_difference (Order 3) for those eight factors over the same `count`
/// starts, into sums[0..7]: each sample is loaded once for all eight and the shifted vectors are
/// formed in registers (AVX-512 only: difference_runs_available(); one accumulator of eight lanes
/// per factor, so the rounding differs from the one-factor kernels' in the last bits).
/// `readable`: the starts k < readable whose largest-factor window lies inside the record (at
/// least count); whole vectors run while they stay inside it, the rest by the one-factor loop.
bool difference_runs_available();
void sum_sq_second_difference_run8(const double* x, std::size_t m, std::size_t count, std::size_t readable,
                                   double* sums);
void sum_sq_third_difference_run8(const double* x, std::size_t m, std::size_t count, std::size_t readable,
                                  double* sums);

/// The phase of n rate samples: out[k] = tau0_s ((sum + compensation) after adding y[0..k] -
/// offset), the running total carried in (sum, compensation) from call to call. Eight samples
/// per step: their running sum within the step in a vector (three shift-adds), then the carried
/// total added to all eight by an error-free two-sum whose errors join the compensation; the
/// serial chain is one add per eight samples instead of Neumaier's add and branch per sample.
void compensated_prefix(const double* rate, std::size_t n, double offset, double tau0_s,
                        double& sum, double& compensation, double* out);

/// Modified-Allan window sums: with e_i = x[i+2m] - 2 x[i+m] + x[i] and the window
/// v_j = sum_{i=j}^{j+m-1} e_i, returns sum_{j<count} v_j^2 (count >= 1). Reads x[0 .. count-2+3m].
/// v_0 is summed directly (O(m)); v_{j+1} = v_j + (e_{j+m} - e_j) then runs eight windows per
/// step as a vector prefix sum. Each e is formed as (x[i+2m] - 2 x[i+m]) + x[i], exact for
/// slowly varying phase, so a pure rate ramp (constant e) leaves every increment exactly zero.
/// Also returns, in *second_sum when given, sum_{k<count-1} e_k^2 (the overlapping Allan terms
/// the recursion reads anyway: R(n) in noise_id.cpp needs both sums from one pass).
double sum_sq_window_second_difference(const double* x, std::size_t m, std::size_t count,
                                       double* second_sum = nullptr);

/// One octave of the modified-Allan windows by doubling (difference_sums.cpp). With
/// D_m(j) = sum_{i=j}^{j+m-1} (x[i+m] - x[i]), the window of factor m is v_j = D_m(j+m) - D_m(j)
/// and the next octave's sums follow without a pass over x: D_2m(j) = D_m(j) + 2 D_m(j+m) +
/// D_m(j+2m). Given d[k] = D_m(k), returns sum_{k<count} (d[k+m] - d[k])^2 and overwrites
/// d[k] with D_2m(k) for k < next (in place: each step reads only entries at or after its own).
/// Reads d[0 .. max(count + m, next + 2m) - 1].
double sum_sq_window_doubling_step(double* d, std::size_t m, std::size_t count, std::size_t next);

/// The first doubling step (m = 1) read from x directly: returns the squares of the count
/// windows of factor 1 and writes D_2(k) - 4 slope into d[k] for k < next. Reads
/// x[0 .. max(count + 1, next + 2)]. A constant subtracted from every x[k+1] - x[k] moves each
/// D_m by m^2 times it and leaves every window D_m(j+m) - D_m(j) as it is; with slope the phase's
/// mean increment, D stays near the size of the windows instead of m^2 times the rate offset.
double sum_sq_window_doubling_first(const double* x, std::size_t count, std::size_t next, double slope,
                                    double* d);

/// Modified-Allan windows down a gathered tile (difference_sums.cpp): rows of 64 phase samples,
/// row r + A starting m samples after row r (lag = 64 A elements). For each of `rows` rows, the
/// windows v(r, c), c = 0..63, with v(r, 0) = v0[r] and v(r, c+1) = v(r, c) + e_{c+m} - e_c
/// (e the second difference at lag m, read down the tile); returns the sum of their squares.
/// Reads tile rows up to rows - 1 + 3A, all 64 columns.
double sum_sq_window_tile_rows(const double* tile, std::size_t lag, const double* v0,
                               std::size_t rows);

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
