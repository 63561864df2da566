#pragma once
// Power-law noise identification at one averaging factor: which alpha (edf.hpp) dominates.
//
// Methods, in the order Stable32 uses them:
//  1. Lag-1 autocorrelation (W. J. Riley and C. A. Greenhall, "Power law noise identification
//     using the lag 1 autocorrelation", Proc. EFTF 2004), when the phase decimated by m has at
//     least kMinLag1AcfPoints points: difference the decimated phase until
//     delta = r1 / (1 + r1) < 0.25 (r1: lag-1 autocorrelation, mean removed) or d = d_max
//     (2 Allan family, 3 Hadamard family). At m = 1, alpha = round(2 - 2 (delta + d)) as in
//     Stable32. At m >= 2 the decimated phase of sampled noise has other delta values than
//     discrete-time noise (flicker FM: about -0.25 instead of -0.5 after two differences), and
//     rounding misreads flicker FM as random-walk FM in ~25% of cases; there the noise type whose
//     Greenhall-Riley model delta is nearest wins (a departure from Stable32, docs/confidence.md).
//  2. Otherwise the B1 bias ratio (Barnes): B1 = (N-sample variance) / (Allan variance) of the
//     N non-overlapping m-averages of rate, compared with its expectation
//     B1(N, mu) = N (1 - N^mu) / (2 (N - 1) (1 - 2^mu))  (mu = 0: N ln N / (2 (N - 1) ln 2)),
//     mu = -alpha - 1 for alpha <= 0 and mu = -2 for white and flicker PM; the nearest mu in the
//     log domain (boundaries at geometric means) wins. It needs N >= kMinB1Averages and
//     resolves alpha = -2..2 only (-3..2 for the Hadamard family).
//  3. When B1 says PM (mu = -2), the ratio R(n) = Mod sigma^2 / sigma^2 (overlapping) separates
//     white PM (R = 1/m) from flicker PM (R from the Greenhall-Riley model: 0.42 at m = 4, 0.24
//     at m = 32); the boundary is their geometric mean. At m = 1 the two are indistinguishable
//     and white PM is reported.
// Accuracy (measured on simulated pure power-law noise, 200 records of 1025 points,
// tests/confidence/test_noise_id.cpp): the lag-1 method returns the simulated alpha in >= 97.5%
// of cases for every FM type and white PM at m = 1..8 (>= 129 decimated points), except
// flicker-walk FM at m = 2 (87.5%); flicker PM only at m = 1 (decimation aliases it toward white
// PM: 76% at m = 4). B1 with 8-30 points is a rough guide (70-90%).
#include <climits>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>
#include <string>
#include <string_view>

#include "imunoise/estimator.hpp"

namespace imunoise {

/// Fewest decimated phase points for the lag-1 autocorrelation method (Riley & Greenhall: ~30).
inline constexpr std::size_t kMinLag1AcfPoints = 30;
/// Fewest non-overlapping rate averages for the B1 ratio (with fewer, its spread spans every
/// noise type: on PHASE.DAT, white FM, it reads 0.69 at m = 128 with 7 averages, "PM").
inline constexpr std::size_t kMinB1Averages = 8;

/// How a noise type was obtained.
enum class NoiseIdMethod {
  lag1_acf,      ///< lag-1 autocorrelation of the decimated phase
  b1_ratio,      ///< B1 bias ratio
  b1_rn_ratio,   ///< B1 said PM; R(n) chose white or flicker PM
  forced,        ///< given by the caller (--noise-type)
  previous_tau,  ///< not identifiable here; the noise type of the next smaller tau (Stable32)
  none,          ///< not identified (message says why)
};

/// "lag1-acf", "b1", "b1+rn", "forced", "previous-tau", "none".
std::string_view noise_id_method_name(NoiseIdMethod method);

/// Result of a noise identification.
struct NoiseId {
  int alpha = std::numeric_limits<int>::min();  ///< identified alpha; INT_MIN when none
  NoiseIdMethod method = NoiseIdMethod::none;
  /// The statistic decided on: lag-1 ACF: the unrounded alpha estimate; B1: the measured B1;
  /// B1 + R(n): the measured R(n). NaN otherwise.
  double statistic = std::numeric_limits<double>::quiet_NaN();
  std::size_t points = 0;  ///< decimated phase points available at this m
  std::string message;     ///< why identification failed (empty on success)
  [[nodiscard]] bool identified() const { return method != NoiseIdMethod::none; }
};

/// Identifies the dominant noise at averaging factor m from phase (angle) samples, for the
/// estimator's family (Allan: -2..2, Hadamard: -4..2). Throws InputError when m = 0, the
/// estimator has no noise identification, or there are too few samples (the message says how
/// many points each method needs and how to force the noise type instead).
NoiseId identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator);

/// As identify_noise, but too few samples (or non-finite data) is reported in the result
/// (method none, message set) instead of thrown. Still throws InputError for m = 0.
NoiseId try_identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator);

/// try_identify_noise with R(n) at m already measured (rn_ratios_for_grid); NaN: measured here.
NoiseId try_identify_noise(std::span<const double> phase, std::size_t m, Estimator estimator,
                           double known_rn);

/// R(n) for a dense grid of factors on a long record, all at once from sums through FFT
/// correlations (src/core/correlation_sums.hpp), where measuring it at each factor (the whole
/// record per factor) would cost more: indexed like `factors`, NaN where B1 cannot call for it,
/// where rn_ratio_sampled samples anyway, or where the sums' rounding bound exceeds 1e-9 relative
/// (a ratio that only chooses between two noise types an octave apart). Empty when not worth it.
std::vector<double> rn_ratios_for_grid(std::span<const double> phase, std::span<const std::size_t> factors,
                                       unsigned threads);

/// R(n) at each of `factors` from the correlation sums, as rn_ratios_for_grid but for every
/// factor with 3m <= N (NaN: the rounding bound exceeds 1e-9 relative, or 3m > N).
std::vector<double> rn_ratios(std::span<const double> phase, std::span<const std::size_t> factors,
                              unsigned threads);

/// True when averaging factor m leaves enough decimated points of n_phase for some method
/// (the B1 ratio needs kMinB1Averages + 1); try_identify_noise reports too few otherwise.
bool noise_identifiable(std::size_t n_phase, std::size_t m);

/// The sentence try_identify_noise reports when !noise_identifiable(n_phase, m): how many
/// points each method needs and how to force the noise type instead.
std::string too_few_for_noise_id(Estimator estimator, std::size_t n_phase, std::size_t m);

// ---- Building blocks (also used by the tests) --------------------------------------------

/// Lag-1 autocorrelation of `values` about their mean; NaN for fewer than 3 values or zero
/// variance.
double lag1_autocorrelation(std::span<const double> values);

/// Unrounded alpha estimate of the lag-1 method on phase decimated by m, differencing at most
/// d_max times; NaN when fewer than d_max + 3 decimated points or the data are degenerate.
double lag1_acf_alpha_estimate(std::span<const double> phase, std::size_t m, int d_max);

/// Measured B1 ratio at m from N phase samples: the sample variance over the Allan variance of
/// the floor((N-1)/m) non-overlapping m-averages of rate; NaN for fewer than 2 averages or zero
/// Allan variance.
double b1_ratio(std::span<const double> phase, std::size_t m);

/// Expected B1 for n_averages averages of noise whose Allan variance goes as tau^mu.
double b1_expected(std::size_t n_averages, double mu);

/// Measured R(n) = Mod sigma^2(m) / sigma^2(m), both overlapping; NaN when phase.size() < 3m.
double rn_ratio(std::span<const double> phase, std::size_t m);

/// R(n) as rn_ratio, from the windows and second differences that start at multiples of q,
/// the largest power of two dividing m that is at most m/64 (q >= min_stride required, else
/// rn_ratio itself is returned; the identification uses min_stride = 64, tests go lower). The windows are still sums of every second difference in them (from
/// prefix sums of the phase at multiples of q, in long double), only 1 in q start points is
/// used: consecutive windows overlap by at least 63/64, so the estimate keeps nearly all of the
/// full one's information while the record is read once, in sequence, instead of at four
/// offsets m apart. Used by the identification at the long taus where B1 calls for R(n).
double rn_ratio_sampled(std::span<const double> phase, std::size_t m,
                        std::size_t min_stride = 64);

/// Expected R(n) at m for noise type alpha in -2..2 (Greenhall-Riley model: 1/m for white PM,
/// 1/2 for white FM at large m, ...); NaN outside.
double rn_expected(int alpha, std::size_t m);

}  // namespace imunoise
