#pragma once
// Noise-model identification: from an overlapping Allan variance curve to the coefficients of
// the paper's eq. 5 (IEEE Std 952-1997 Annex C), each with a confidence interval and a verdict on
// whether the record can support it.
//
// Model (SI, rate unit U = rad/s for a gyro):
//   sigma^2(tau) = 3 Q^2/tau^2 + N^2/tau + (2 ln 2/pi) B^2 + K^2 tau/3 + R^2 tau^2/2
// is linear in theta = (Q^2, N^2, B^2, K^2, R^2) >= 0.
//
// Methods (docs/fit.md has the derivations and the measured accuracy):
//  - wls (default): non-negative least squares on sigma^2(tau) weighted by the variance of each
//    estimate *under the fitted model* (iterated: the weights come from the model, not from the
//    noisy curve). The overlapping estimates at neighbouring taus are strongly correlated; their
//    full covariance matrix is computed analytically from the model (curve_covariance below)
//    and enters the coefficient covariance through the sandwich A Sigma A' of the estimator
//    actually used (FitOptions::use_correlation also whitens the fit with it: GLS). A term
//    that dominates the fitted model at fewer than min_dominant_taus taus is dropped and the
//    rest refitted (data sufficiency).
//  - ols: the paper's ordinary (unweighted, unconstrained) least squares on the eq. 5
//    polynomial, for reproduction. A negative variance coefficient is reported as
//    not identified (the paper printed |.|). Its covariance is the sandwich
//    (G'G)^-1 G' Sigma G (G'G)^-1 with the same model covariance Sigma.
//  - slope: IEEE 952 / MATLAB read-off: the tangent of slope -1/2 at tau = 1 s (N), +1/2 at
//    tau = 3 s (K), -1 at sqrt(3) s (Q), +1 at sqrt(2) s (R) and the floor / 0.6643 (B). Each
//    tangent is the lowest line of its slope touching the curve (min over tau of
//    sigma^2(tau) / g_j(tau), over the taus with N/m >= 5, i.e. at least 4 rough degrees of
//    freedom); its interval is the chi-squared interval of the touching
//    point. A tangent touching where the curve's local slope is not within 0.25 of the
//    term's slope is an upper limit only: the term is then reported as not identified.
//
// Uncertainty (wls, ols): a level-L interval on theta_j by test inversion: h is inside when
// the estimate lies within the level range of its modelled distribution under theta_j = h
// (h chi^2(nu_h)/nu_h plus normal noise from the other terms, both from the sandwich
// covariance evaluated with the model at h), mapped through the square root. Validated by
// coverage on simulated 6 h TG-100 records (tests/fit/test_acceptance.cpp; docs/fit.md:
// N 94 %, B 92 %, K 98 % over 200 runs).
//
// Real sensors (docs/fit.md): by default the shortest taus bent by the sensor's
// sampling chain and interior bumps (concave bends: no sum of power laws has one) are left out,
// a model-mismatch scatter is estimated when chi^2 rejects the model (weights and intervals
// include it), and the flicker column's shape at the shortest taus carries the band-edge
// ambiguity (FitOptions::exclude_distorted, model_mismatch, flicker_band_edge). When chi^2
// rejects the power laws and the curve has a bump, the Gauss-Markov and sinusoid terms are
// tried automatically and kept only when the data support them (FitOptions::auto_extra_terms).
//
// Identification: a term is identified when zero is outside its interval. Otherwise its value
// is 0, identified = false, ci_low = 0 and ci_high holds the upper limit, with a note saying
// why (not significant, clamped at zero, too few taus, negative ols coefficient, not fitted).
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/fit/extra_terms.hpp"
#include "imunoise/fit/gmwm.hpp"
#include "imunoise/noise_coefficients.hpp"

namespace imunoise::fit {

/// gmwm: the Generalized Method of Wavelet Moments (gmwm.hpp) on the dyadic taus of the curve,
/// with several Gauss-Markov terms and WVIC model selection (FitOptions::gmwm).
enum class Method { wls, ols, slope, gmwm };
/// "wls", "ols", "slope", "gmwm".
std::string method_name(Method method);
/// Parses "wls", "ols", "slope" or "gmwm"; InputError otherwise.
Method parse_method(std::string_view text);

/// Indices of the five power-law terms in theta and in every per-term array; the optional
/// terms (extra_terms.hpp) follow them where a model index is needed (dominant_term).
enum Term : int { kQ = 0, kN = 1, kB = 2, kK = 3, kR = 4, kGM = 5, kSIN = 6 };
inline constexpr int kTermCount = 5;
/// "Q", "N", "B", "K", "R", and "GM", "SIN" for the optional terms.
const char* term_name(int term);

/// The coefficient of term j (kQ .. kR) in c.
Coefficient& coefficient(NoiseCoefficients& c, int term);
const Coefficient& coefficient(const NoiseCoefficients& c, int term);

/// Basis function g_j(tau) of term j: sigma^2(tau) = sum_j theta_j g_j(tau).
double term_basis(int term, double tau_s);

/// Model selection among the fitted terms (wls): each subset of terms is fitted and the one
/// minimising chi^2 + penalty * (number of terms) is kept; a term left out is not identified.
enum class Selection {
  none,  ///< plain non-negative least squares: every term with a positive estimate stays
  aic,   ///< Akaike: penalty 2 per term
  bic,   ///< Bayesian (Schwarz): penalty ln(number of taus) per term
};

struct FitOptions {
  Method method = Method::wls;
  /// Terms to fit (true = fitted). Q, N, B, K, R by default. A term left out is reported as
  /// not identified with the note "not fitted".
  /// R is off by default: at the end of a record a ramp and a rate random walk are hard to
  /// tell apart and a free R was falsely identified in ~25% of simulated 6 h TG-100 records
  /// (docs/fit.md); ask for it (--terms Q,N,B,K,R) when a ramp is expected.
  bool terms[kTermCount] = {true, true, true, true, false};
  /// Optional terms (wls only; extra_terms.hpp): tested, kept when the data support them.
  bool gauss_markov = false;
  bool sinusoid = false;
  /// wls: try the Gauss-Markov and sinusoid terms automatically when neither is requested,
  /// the chi^2 test rejects the power-law model (model_mismatch) and the curve has a bump
  /// beyond the sampling chain (a concave bend: no sum of power laws has one). The search
  /// starts from the bumps (T_c = tau / 1.89, f0 = 0.371 / tau) and the grids; a term is kept
  /// by the same BIC / dominance / interval rules as a requested one, with a warning naming
  /// it; with no term kept the power-law fit stands. false: --no-auto-terms.
  bool auto_extra_terms = true;
  double level = 0.95;          ///< two-sided confidence level of every interval, 0 < L < 1
  int max_iterations = 8;       ///< wls re-weighting iterations (>= 1)
  /// Stop when every theta_j changes by less than this fraction of its standard deviation.
  double parameter_tolerance = 1e-3;
  /// wls only: whiten with the full model covariance (true: generalised least squares) or
  /// with its diagonal (false, default; the coefficient covariance is then the sandwich with
  /// the full covariance, so the correlations are still accounted for in the intervals). The
  /// diagonal weights gave the smaller K error on the acceptance study (docs/fit.md).
  bool use_correlation = false;
  Selection selection = Selection::none;
  /// wls: a term must dominate the fitted model at this many taus or more to stay in the fit
  /// (data sufficiency); otherwise it is reported as not identified and the rest refitted.
  int min_dominant_taus = 2;  ///< wls: which terms are present (see Selection)
  /// Taus fitted: [tau_min_s, tau_max_s] (0: no limit). Taus outside are reported in
  /// FitSummary::excluded_taus and in the residuals with used = false.
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  /// wls, ols: leave out the shortest taus that a sensor's sampling chain (anti-alias filter,
  /// decimation, an axis updated at a fraction of the output rate) has bent away from any sum
  /// of power laws. eq. 5 is a sum of power laws of tau, so log sigma^2 is a convex function of
  /// log tau: a concave bend (the log-log slope falling by more than 3 standard deviations of
  /// its sampling noise) at an averaging factor m <= distortion_max_m cannot come from the
  /// noise model; every tau below the last such bend is excluded, with a note.
  bool exclude_distorted = true;
  std::size_t distortion_max_m = 16;
  /// wls: model mismatch (ols, the paper's unweighted method, is left as it was: its estimate
  /// does not minimise chi^2, so the test below would reject exact models). When the chi^2 of the fit (full model covariance,
  /// each tau's residual its cube-root score: FitSummary::chi2) exceeds its
  /// (1 - mismatch_test_alpha) quantile, the power-law model does not describe the curve to
  /// within its sampling noise (a real sensor: temperature, a sinusoid, a non-1/f floor). A
  /// relative scatter s of the curve about the model is then estimated (Paule-Mandel: chi^2 =
  /// dof with the covariance Sigma + s^2 diag(model^2)) and used in the weights and in every
  /// interval, so that no tau is trusted beyond the model's own accuracy and the intervals are
  /// widened by the mismatch. false: exact-model weights (the fitted curve's own sampling noise only).
  bool model_mismatch = true;
  /// wls, ols: the flicker floor at the shortest taus. eq. 5's (2 ln 2/pi) B^2 is the Allan
  /// variance of continuous 1/f rate noise integrated over each sample; discrete 1/f noise
  /// whose spectrum runs to the Nyquist frequency (Kasdin-Walter) exceeds it by 44 % at m = 1,
  /// 15 % at 2, 5 % at 4, 1.5 % at 8. The curve cannot tell the two apart (N dominates there
  /// ~1000:1), yet the excess, attributed to N, biased N by +0.015 % = 0.42 interval sd on 6 h
  /// records (26/30 coverage; the bias is per sample, so it grows against the interval with the
  /// record length). true: the flicker column takes the midpoint of the two and carries half
  /// their difference as a fully correlated systematic error in the covariance.
  bool flicker_band_edge = true;
  double mismatch_test_alpha = 1e-3;
  /// method gmwm: its terms (GM repeated, or automatic), bootstrap and seed. The curve is
  /// prepared as for wls (tau range, sampling-chain cut); terms[] and gauss_markov/sinusoid
  /// are not used.
  GmwmOptions gmwm;
  /// Checks every field; writes why not into *error (may be null).
  bool IsValid(std::string* error) const;
};

/// How the fit ended. Each value says what the coefficients mean.
enum class Termination {
  converged,          ///< parameters stable to parameter_tolerance: coefficients are usable
  no_convergence,     ///< max_iterations reached: coefficients are the last iterate, usable with care
  too_few_points,     ///< fewer usable taus than fitted terms: nothing identified
  degenerate_input,   ///< zero, constant or non-finite curve: nothing identified
};
std::string termination_name(Termination termination);

/// Diagnostics at one tau of the curve.
struct TauResidual {
  double tau_s = 0.0;
  double avar = 0.0;        ///< measured sigma^2 (SI)
  double avar_model = 0.0;  ///< fitted model sigma^2 (SI)
  double sd_model = 0.0;    ///< standard deviation of the estimate under the model (SI)
  double normalized = 0.0;  ///< (avar - avar_model) / sd_model
  int dominant_term = -1;   ///< term contributing most to avar_model (kQ..kSIN; -1: none)
  bool used = true;         ///< false: left out of the fit (FitSummary::excluded_taus says why)
};

/// A tau of the curve that the fit left out, and why.
struct ExcludedTau {
  double tau_s = 0.0;
  std::string reason;  ///< "sampling_chain", "bend" (an interior bump) or "tau_range"
};

/// Per-term detail behind the coefficient.
struct TermFit {
  bool fitted = false;
  double theta = 0.0;        ///< estimated variance coefficient (SI^2), >= 0 for wls
  double theta_sd = 0.0;     ///< its standard deviation from the model covariance
  double estimate = 0.0;     ///< sqrt(max(theta, 0)): the point estimate before the verdict
  double tau_min_s = 0.0;    ///< tau range where the term dominates the fitted model (0 0: none)
  double tau_max_s = 0.0;
};

struct FitSummary {
  Termination termination = Termination::degenerate_input;
  int iterations = 0;
  std::size_t points_used = 0;
  /// r' Sigma^-1 r with the model covariance (correlations included), each tau's r the cube-root
  /// score of its estimate ((a_hat / a)^(1/3) against its chi-square law, times its sd; a_hat - a
  /// for many degrees of freedom): honest where the long taus have few (docs/fit.md)
  double chi2 = 0.0;
  std::size_t dof = 0;        ///< points_used - free parameters
  double chi2_dof = 0.0;      ///< chi2 / dof (0 when dof = 0)
  /// Relative scatter of the curve about the model estimated from the misfit (model_mismatch;
  /// 0 when the chi^2 test accepts the model) and chi^2/dof with it in the covariance (~1).
  double mismatch_scatter = 0.0;
  double chi2_dof_with_mismatch = 0.0;
  /// Taus left out of the fit (sampling-chain distortion, --tau-min/--tau-max).
  std::vector<ExcludedTau> excluded_taus;
  std::vector<std::string> warnings;
  std::string message;        ///< one sentence on the termination
  std::string BriefReport() const;
  std::string FullReport() const;
};

struct FitResult {
  NoiseCoefficients coefficients;  ///< SI; not identified terms have value 0
  TermFit terms[kTermCount];
  std::vector<TauResidual> residuals;
  /// Paper eqs. 1-2 from the fitted N and K (SI): tau_opt = sqrt(3) N / K,
  /// sigma^2_min = 2 N K / sqrt(3); NaN-free: 0 when N or K is zero.
  double tau_opt_s = 0.0;
  double avar_min_eq2 = 0.0;
  /// The measured curve's own minimum (SI variance) and where it is.
  double avar_min_measured = 0.0;
  double tau_min_measured_s = 0.0;
  FitSummary summary;
  /// The tests of the optional terms; their coefficients are in coefficients.gauss_markov /
  /// coefficients.sinusoid (set whenever the term was requested).
  ExtraTermsReport extras;
  /// method gmwm: the whole GMWM result (every term, its GM terms by correlation time, the
  /// candidates' table, the J test, the wavelet variances). The power-law terms are also in
  /// coefficients; the GM terms only here (NoiseCoefficients holds one GM term).
  std::optional<GmwmResult> gmwm;
};

/// Fits the noise model to an oadev curve (points from compute_deviation(oadev, ...), SI).
/// n_phase: number of phase samples of the record (needed for the estimate covariance).
/// Throws InputError when options are invalid; numerical outcomes are in summary.termination.
/// phase_si: the record's n_phase phase samples, needed by method gmwm with gmwm.robust only
/// (its estimates come from the samples).
FitResult fit_allan(std::span<const DevPoint> oadev_points, std::size_t n_phase,
                    double tau0_s, const FitOptions& options = {},
                    std::span<const double> phase_si = {});

/// Checks a record before fitting: non-finite values and fewer than 5 samples throw
/// InputError; saturation (more than 0.1% of the rate samples at the extreme value) and
/// quantization (fewer than 64 distinct rate values) give warnings. Looks at the first 1e6
/// rate samples (first differences of the phase).
std::vector<std::string> record_warnings(std::span<const double> phase_si, double tau0_s);

/// True when the rate (first differences of the phase) is constant to 1e-9 relative, all-zero
/// data included: its Allan curve would be rounding noise, which must not be fitted.
bool is_constant_record(std::span<const double> phase_si, double tau0_s);

/// Covariance matrix (row-major, size k x k) of the overlapping Allan variance estimates at
/// averaging factors m_list (n_phase phase samples, spacing tau0_s) for a Gaussian process
/// with the model theta (Q^2, N^2, B^2, K^2, R^2). A rate ramp is deterministic and would add
/// no variance, which lets a fit lean on the last, noisiest taus; it is therefore given the
/// variance of the rate random walk with the same Allan variance at the pair's taus
/// (theta_K += 1.5 R^2 sqrt(tau_i tau_j)): a ramp seen in an Allan curve is rarely exactly
/// deterministic over the record, and this keeps its weight honest.
/// Computed exactly from the generalised covariance of the phase of each term
/// (N: -N^2 |t|/2, B: B^2 t^2 ln|t| / (2 pi), K: K^2 |t|^3 / 12, Q: Q^2 at lag 0) by Isserlis'
/// theorem: Cov(s_i, s_j) = 2 sum_k sum_l Cov(a_k, b_l)^2 / (4 tau_i^2 tau_j^2 n_i n_j); the
/// lag sum is done exactly on short pieces and by Gauss-Legendre quadrature with the
/// Euler-Maclaurin end correction on long ones (relative accuracy ~1e-6 for N and K; Q is
/// included only where the lag support is short, where it matters).
/// The same covariance as a quadratic form in theta, precomputed for one curve layout: the
/// construction does the lag sums (about 10 ms for 22 octave taus), covariance() is then
/// O(k^2) for any theta.
/// gm_time_s > 0 adds a first-order Gauss-Markov term with that correlation time (phase
/// covariance -sigma^2 (T^2 e^-|t|/T + T |t|)); its variance sigma^2 is then an argument of
/// covariance(). Construction takes longer with it (its pieces are cut finer).
class CovarianceBasis {
 public:
  CovarianceBasis(std::span<const std::size_t> m_list, std::size_t n_phase, double tau0_s,
                  double gm_time_s = 0.0);
  /// Row-major k x k covariance for theta = (Q^2, N^2, B^2, K^2, R^2) and the Gauss-Markov
  /// variance sigma^2 (ignored without gm_time_s); negative entries are treated as 0.
  std::vector<double> covariance(std::span<const double> theta, double gm_variance = 0.0) const;
  std::size_t size() const { return k_; }
  double gm_time_s() const { return gm_time_s_; }

 private:
  std::size_t k_;
  std::vector<double> products_;  // (i, j, product) -> sum
  std::vector<double> tau_s_;
  double gm_time_s_ = 0.0;
};

std::vector<double> curve_covariance(std::span<const std::size_t> m_list, std::size_t n_phase,
                                     double tau0_s, std::span<const double> theta);

}  // namespace imunoise::fit
