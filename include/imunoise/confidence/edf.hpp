#pragma once
// Equivalent degrees of freedom (EDF) of the deviation estimators under power-law noise.
//
// A variance estimate s^2 of sigma^2 is treated as s^2 ~ sigma^2 * chi^2(edf) / edf; the EDF
// fixes the width of the chi-squared confidence interval (interval.hpp).
//
// Noise types are named by alpha, the exponent of the rate (fractional-frequency) PSD
// S_y(f) ~ f^alpha:
//   alpha =  2  white PM   (white angle noise)
//   alpha =  1  flicker PM (flicker angle noise)
//   alpha =  0  white FM   (angle random walk N)
//   alpha = -1  flicker FM (bias instability B)
//   alpha = -2  random-walk FM (rate random walk K)
//   alpha = -3  flicker-walk FM,  alpha = -4  random-run FM (Hadamard family only)
//
// Method: C. A. Greenhall and W. J. Riley, "Uncertainty of stability variances based on finite
// differences", Proc. 35th PTTI Meeting, 2003 (the algorithm Stable32 uses), full version: the
// truncated "BasicSum" of squared autocovariances for J <= 100, the paper's asymptotic tables
// (a0 - a1/r)/r otherwise, and the closed form for white PM. Accuracy: the EDF of the paper's
// model (phase = first difference of a continuous-time power-law process), which is what
// Stable32 reports: on PHASE.DAT (NBS14) oadev m=1: 782.03, m=128: 9.5508; mdev m=2: 479.00;
// hdev m=2: 271.97 (tests/confidence/test_edf.cpp). The tables are the paper's, checked against
// the asymptotic integrals they come from to their printed precision.
#include <cstddef>
#include <limits>
#include <optional>
#include <string_view>

#include "imunoise/estimator.hpp"

namespace imunoise {

/// Smallest and largest power-law exponent alpha the library knows (random-run FM, white PM).
inline constexpr int kMinNoiseAlpha = -4;
inline constexpr int kMaxNoiseAlpha = 2;

/// Name of a noise type: "white PM", "flicker PM", "white FM", "flicker FM", "random-walk FM",
/// "flicker-walk FM", "random-run FM"; "unknown" outside -4..2.
std::string_view noise_type_name(int alpha);

/// Short name, as Stable32 prints it: "WHPM", "FLPM", "WHFM", "FLFM", "RWFM", "FWFM", "RRFM".
std::string_view noise_type_abbreviation(int alpha);

/// Parses a noise type for --noise-type: an integer alpha in -4..2 ("-1"), or a Stable32
/// abbreviation or its short form, case-insensitive: WHPM/WPM, FLPM/FPM, WHFM/WFM, FLFM/FFM,
/// RWFM, FWFM, RRFM. Throws InputError listing the accepted forms.
int parse_noise_type(std::string_view text);

/// How an EDF value was obtained.
enum class EdfMethod {
  greenhall_riley,  ///< Greenhall & Riley 2003 (Allan, modified Allan, Hadamard families)
  sp1065,           ///< NIST SP 1065 formulas/tables (total family and Theo1; see total_edf)
  ieee952_simple,   ///< rough IEEE 952 fallback edf = N/m - 1, noise-type blind: used only where
                    ///< nothing better is defined (no noise type could be identified)
  not_available,    ///< no EDF: alpha outside the estimator's domain, too few data, or an
                    ///< estimator without a defined EDF in this build
};

/// "greenhall-riley", "sp1065", "ieee952-simple", "not-available".
std::string_view edf_method_name(EdfMethod method);

/// An EDF with the method that produced it; value is NaN when method == not_available.
struct Edf {
  double value = std::numeric_limits<double>::quiet_NaN();
  EdfMethod method = EdfMethod::not_available;
};

/// The finite-difference structure of an estimator in Greenhall & Riley's terms.
struct DifferenceVariance {
  int d = 2;              ///< order of the phase difference: 2 Allan, 3 Hadamard
  bool modified = false;  ///< differences of tau-averaged phase (filter factor F = 1), else F = m
  bool overlapping = false;  ///< stride tau0 (stride factor S = m), else stride tau (S = 1)
};

/// The structure of `estimator`, or nullopt for estimators outside the Allan/Hadamard families
/// (the total family, Theo1, MTIE and TIE rms).
std::optional<DifferenceVariance> difference_variance(Estimator estimator);

/// The finite-difference estimator whose noise identification and noise-type domain an
/// estimator shares: itself for the Allan/Hadamard families; oadev for totdev and theo1, mdev
/// for mtotdev and ttotdev, ohdev for htotdev; nullopt for mtie and tierms (no noise model).
std::optional<Estimator> finite_difference_proxy(Estimator estimator);

/// Whether the estimator converges for noise type alpha (alpha + 2d > 1): -2..2 for the Allan
/// family (adev, oadev, mdev, tdev) and for totdev, mtotdev, ttotdev, theo1; -4..2 for the
/// Hadamard family and htotdev; never for mtie and tierms.
bool alpha_in_domain(Estimator estimator, int alpha);

/// NIST SP 1065 EDF of the total family and Theo1 (N = n_phase, T/tau = N/m as Stable32):
///   totdev  (SP 1065 Table 7):  b N/m - c; alpha 0: (1.50, 0), -1: (1.17, 0.22), -2: (0.93, 0.36);
///           for white and flicker PM (no entry) the oadev Greenhall-Riley EDF, a lower bound.
///   mtotdev, ttotdev (Table 8): b N/m - c; alpha 2: (1.90, 2.10), 1: (1.20, 1.40),
///           0: (1.10, 1.20), -1: (0.85, 0.50), -2: (0.75, 0.31).
///   htotdev (Howe et al., PTTI 2000, as in Stable32): m < 16 and alpha without an entry: the
///           ohdev Greenhall-Riley EDF; otherwise (N/m) / (b0 + b1 m/N); alpha 0: (0.559, 1.004),
///           -1: (0.868, 1.140), -2: (0.938, 1.696).
///   theo1 (Howe & Peppler 2003; SP 1065 sec. 5.2.15), r = 0.75 m:
///     alpha  2: 0.86 (N+1)(N - 4r/3) / (N - r) * r / (r + 1.14)
///     alpha  1: (4.798 N^2 - 6.374 N r + 12.387 r) / (sqrt(r + 36.6) (N - r)) * r / (r + 0.3)
///     alpha  0: ((4.1 N + 0.8)/r - (3.1 N + 6.5)/N) * r^1.5 / (r^1.5 + 5.2)
///     alpha -1: (2 N^2 - 1.3 N r - 3.5 r) / (N r) * r^3 / (r^3 + 2.3)
///     alpha -2: (4.4 N - 2)/(2.9 r) * ((4.4 N - 1)^2 - 8.6 r (4.4 N - 1) + 11.4 r^2) / (4.4 N - 3)^2
/// Returns {NaN, not_available} outside these domains (and always for mtie, tierms).
Edf total_edf(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase);

/// Greenhall & Riley EDF of a d-th difference variance estimator at averaging factor m over
/// n_phase phase samples, for integer alpha in -4..2. NaN when alpha + 2d <= 1, m = 0, or
/// n_phase is shorter than one difference (n_phase < m/F + m d). Pure function; O(1) work
/// (at most ~100 autocovariance terms).
double greenhall_riley_edf(int alpha, const DifferenceVariance& variance, std::size_t m,
                           std::size_t n_phase);

/// The same, "simple" version of the paper (BasicSum truncated at J = min(M, (d+1) S) for every
/// J, no tables): exact for the model but O(J) work, J up to (d+1) m. For checks and studies.
double greenhall_riley_edf_simple(int alpha, const DifferenceVariance& variance, std::size_t m,
                                  std::size_t n_phase);

/// Rough EDF from the IEEE Std 952 relative standard error 1/sqrt(2 (N/m - 1)) of a deviation:
/// edf = n_phase/m - 1 (N = n_phase). Noise-type blind; NaN when that is not positive.
double ieee952_edf(std::size_t m, std::size_t n_phase);

/// EDF of `estimator` at averaging factor m over n_phase phase samples for noise type alpha.
/// Allan and Hadamard families: Greenhall & Riley (tdev shares mdev's EDF); total family and
/// Theo1: total_edf() (SP 1065). Returns
/// {NaN, not_available} when alpha is outside the estimator's domain or the data are too short,
/// and for mtie and tierms, which have no chi-squared EDF (never throws for those).
/// The IEEE 952 fallback is not substituted here; fill_confidence() uses it, labelled, only when
/// no noise type is known.
Edf edf(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase);

}  // namespace imunoise
