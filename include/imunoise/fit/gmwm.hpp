#pragma once
// GMWM: the Generalized Method of Wavelet Moments (Guerrier, Skaloud, Stebler, Victoria-Feser,
// JASA 2013; Stebler et al., IEEE TAES 2014) for composite sensor noise: white rate noise,
// random walk, drift, quantization, flicker and *several* first-order Gauss-Markov (AR1)
// processes, with model selection by the wavelet variance information criterion (WVIC).
//
// Moments. The Haar wavelet variance at dyadic scale tau_j = 2^j tau0 is half the overlapping
// Allan variance at that tau: nu^2(tau_j) = AVAR(tau_j) / 2 (the MODWT Haar coefficients are
// half the difference of adjacent window means). The estimates are the engine's overlapping
// Allan variance (allan.hpp) at the dyadic factors of the curve; no second estimator. Inside,
// everything is written in Allan variance (2 nu^2): the objective is invariant to the factor.
//
// Exact Allan variance (= 2 nu^2) of each term at tau = m tau0, for the *sampled* series:
//   Q  white angle noise (sd Q at the sample instants)       3 Q^2 / tau^2              exact
//   N  white rate noise (per-sample sd N / sqrt(tau0))        N^2 / tau                  exact
//   K  rate random walk averaged over each sample             K^2 tau / 3                exact
//      (a point-sampled discrete random walk y_k = y_{k-1} + K sqrt(tau0) w_k has
//      K^2 tau / 3 + (K^2 tau0^2 / 6) / tau: the same K plus a white N^2 of K^2 tau0^2 / 6)
//   R  rate ramp R t                                          R^2 tau^2 / 2              exact
//   B  flicker rate noise                                     (2 ln 2 / pi) B^2          (the
//      continuous floor of eq. 5, as the wls fit; not exact within a few tau0 of the edges)
//   GM first-order Gauss-Markov, as the AR1 of the samples: y_k = phi y_{k-1} + e_k,
//      phi = exp(-tau0 / T_c), stationary variance sigma^2 (exact recursion of the
//      point-sampled Ornstein-Uhlenbeck process):
//        AVAR(m) = sigma^2 / m^2 [ m (1 + phi) / (1 - phi) - phi (3 - 4 phi^m + phi^2m) / (1 - phi)^2 ]
//      (m = 1: sigma^2 (1 - phi)). The sample-averaged (integrating) Gauss-Markov process of
//      sim/gauss_markov.hpp is this AR1 with variance sigma^2 4 sinh^2(x/2) / x^2 (x = tau0 /
//      T_c) *minus* white noise of per-sample variance sigma^2 [4 sinh^2(x/2) - 2 (x - 1 +
//      e^-x)] / x^2 (~ sigma^2 x / 3): the two differ at tau ~ tau0 when T_c ~ tau0 and
//      coincide for T_c >> tau0. gmwm_avar_ar1 is exact for the AR1; the bootstrap converts.
//   SIN A sin(2 pi f0 t + phase) averaged over each sample    A^2 (sin^2(pi f0 tau) / (pi f0 tau))^2
//   BGM flicker B written as a fixed sum of AR1 terms         B^2 sum_i w_i AVAR_AR1(T_i, m)
//      (gmwm_flicker.hpp: T_i two per decade over the curve's span, w_i such that the sum is the
//      floor (2 ln 2 / pi) to a stated ripple): one parameter, exact for the sampled AR1 sum,
//      and the states a Kalman filter can carry (sigma_i = B sqrt(w_i), T_i)
//
// Estimator. theta minimises (a_hat - a(theta))' W (a_hat - a(theta)) over the log of every
// variance and every T_c (positivity by reparametrisation), W = Sigma(theta)^-1 the inverse of
// the analytic covariance of the estimates (Isserlis: the wls fit's CovarianceBasis extended
// by one AR1 kernel per Gauss-Markov term: GmwmCovarianceBasis below), iterated at the fitted
// model. Levenberg-Marquardt in the log parameters from several starts: the variances by
// non-negative least squares for each set of T_c starts, the T_c from the curve's bumps and
// from grids a decade apart over the curve's tau span (never from constants tuned to a record).
//
// J test: e' [(I - P) S (I - P)]^+ e with e = Wh r the whitened residual, r_i the cube-root score
// of scale i, ((a_hat_i / a_i)^(1/3) - E) / sd of (chi^2_nu / nu)^(1/3), times sqrt(Sigma_ii) (for
// a large nu, a_hat_i - a_i; the long scales' skew taken out, docs/fit.md),
// S = Wh Sigma Wh' and P the projector on the whitened Jacobian: the residual's own covariance
// (delta method), so the statistic is chi^2(k - p) for an exact Gaussian model whatever W is; with
// the efficient W and large nu it is Hansen's (1982) J = min objective. WVIC (Stebler et al. 2014)
// takes the objective itself:
//   WVIC = objective + 2 tr(W Cov(a_hat, a(theta_hat))),   Cov(a_hat, a(theta_hat)) = Sigma W D (D' W D)^+ D'
// (D the Jacobian in the log parameters; delta method), an estimate of the prediction risk
// E[(a* - a(theta_hat))' W (a* - a(theta_hat))] of an independent copy a*, as Mallows' Cp.
// With Sigma the candidate's own model covariance and W common to all candidates.
//
// Intervals: asymptotic (delta method, Cov(log theta) = (D' W D)^-1 D' W Sigma W D (D' W D)^-1, the
// sandwich,
// on the log scale so that they stay positive) and, with bootstrap > 0, the parametric
// bootstrap from the fitted model (sim::ChannelGenerator, seeded, threads): percentile intervals
// of the log parameters. The asymptotic interval reported is the hull of the Wald interval, the
// profile interval and the profile around any other optimum within the rise (docs/fit.md). A
// term whose log variance runs to the floor (the objective does not
// need it) or whose T_c leaves the span of the curve's taus is reported not identified.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/fit/gmwm_flicker.hpp"
#include "imunoise/noise_coefficients.hpp"

namespace imunoise::fit {

enum class GmwmTerm { Q, N, B, K, R, GM, SIN, BGM };
/// "Q", "N", "B", "K", "R", "GM", "SIN", "BGM".
const char* gmwm_term_name(GmwmTerm term);

/// Unit-intensity Allan variance (2 x the Haar wavelet variance) at tau = m tau0 of each term
/// (SI; see the header comment for the forms and their exactness).
double gmwm_avar_quantization(double tau_s);                      // Q = 1
double gmwm_avar_white(double tau_s);                             // N = 1
double gmwm_avar_flicker(double tau_s);                           // B = 1
double gmwm_avar_random_walk(double tau_s);                       // K = 1
double gmwm_avar_ramp(double tau_s);                              // R = 1
double gmwm_avar_ar1(double tc_s, double tau0_s, std::size_t m);  // sigma = 1
double gmwm_avar_sinusoid(double f_hz, double tau_s);             // A = 1

/// Covariance of the overlapping Allan variance estimates at averaging factors m_list under
/// power-law terms plus AR1 (GM) terms with the listed correlation times (AR1 kernel of the
/// point-sampled process, C(t) = -sigma^2 (A e^-|t|/T + B |t|) with A = tau0^2 phi / (1 -
/// phi)^2, B = tau0 (1 + phi) / (2 (1 - phi)): its second differences on the sample lattice are
/// -tau0^2 sigma^2 phi^|d|). Same construction as CovarianceBasis (fit.hpp); at most 6 AR1 terms.
class GmwmCovarianceBasis {
 public:
  static constexpr std::size_t kMaxAr1 = 6;
  /// flicker = false leaves the flicker kernel out (a model without B: faster, its variance
  /// must then be 0); threads: pairs of scales summed in parallel (0: all hardware threads;
  /// the result does not depend on it).
  /// mixture (may be null): a flicker mixture (BGM) as one more random term whose kernel is
  /// the w_i-weighted sum of its AR1 kernels; it counts as one of the kMaxAr1.
  GmwmCovarianceBasis(std::span<const std::size_t> m_list, std::size_t n_phase, double tau0_s,
                      std::span<const double> ar1_times_s, bool flicker = true, unsigned threads = 1,
                      const FlickerMixture* mixture = nullptr);
  /// theta = (Q^2, N^2, B^2, K^2, R^2) (R as in CovarianceBasis: a rate random walk of equal
  /// Allan variance), ar1_variances one sigma^2 per AR1 term, mixture_b2 the B^2 of the
  /// mixture (ignored without one). Row-major k x k.
  std::vector<double> covariance(std::span<const double> theta,
                                 std::span<const double> ar1_variances, double mixture_b2 = 0.0) const;
  std::size_t size() const { return k_; }

 private:
  std::size_t k_;
  std::size_t randoms_;  // 4 + number of AR1 terms (+ 1 for a mixture, last)
  bool mixture_ = false;
  std::vector<double> products_;
  std::vector<double> tau_s_;
};

struct GmwmOptions {
  /// The model: each entry one term; GM may repeat (N,K,GM,GM,GM). Ignored when automatic.
  std::vector<GmwmTerm> terms = {GmwmTerm::N, GmwmTerm::K, GmwmTerm::GM};
  /// --terms auto: nested candidates (white + 0..max_gm GM, with and without K, and each
  /// again with one sinusoid when auto_sinusoid) ranked by WVIC; the table is in
  /// GmwmResult::candidates.
  bool automatic = false;
  int max_gm = 4;
  bool auto_sinusoid = true;
  double level = 0.95;
  /// Re-computations of W at the fitted model (the first W is at the start model).
  int weight_iterations = 3;
  /// Levenberg-Marquardt iterations per start (>= 1); the best start of a fit, should it stop
  /// at the limit, is continued up to nine more times as long. A fit that still reaches it has
  /// status no_convergence and none of its terms is identified (the last iterate is no estimate).
  int max_iterations = 200;
  /// W = Sigma^-1 (the efficient weight, true, default) or diag(Sigma)^-1 (false). Measured
  /// (docs/fit.md): with the full inverse the GM terms are estimated far better (1 h records:
  /// every parameter's interval covered 20/20) but where a random walk dominates the long,
  /// strongly correlated taus the fit can pass below the whole curve (Peelle's pertinent puzzle
  /// of correlated errors): on exact white + random-walk records J rejected 9/30 at 5 %; with the
  /// diagonal weight J rejected 5/30 (honest) but the GM coverage fell to 12-18/20. Intervals
  /// and J account for the correlations in either case (sandwich; generalised J).
  bool full_weight = true;
  /// Parametric bootstrap replicates (0: asymptotic intervals only), its seed and threads
  /// (0: all hardware threads; results do not depend on it).
  int bootstrap = 0;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  /// BGM: correlation times per decade of its mixture (gmwm_flicker.hpp; 1..4).
  int flicker_states_per_decade = 2;
  /// Robust GMWM (Guerrier, Molinari, Victoria-Feser, JASA 2014): each scale's wavelet variance
  /// is a Tukey-biweight M-estimate of the scale of the Haar coefficients (robust_wavelet.hpp),
  /// tuned for robust_efficiency at the Gaussian and Fisher-consistent there; the covariance of
  /// the estimates is the analytic one divided by that efficiency. Needs the phase samples.
  bool robust = false;
  double robust_efficiency = 0.6;
  bool IsValid(std::string* error) const;
};

/// Parses "N,K,GM,GM" (Q N B K R GM SIN BGM, GM repeated) or "auto"; InputError otherwise.
void parse_gmwm_terms(std::string_view list, GmwmOptions& options);

/// One term of the fitted model, SI.
struct GmwmTermEstimate {
  GmwmTerm kind = GmwmTerm::N;
  /// Q, N, B, K, R: the coefficient; GM: sigma (rate); SIN: amplitude (rate). Interval:
  /// asymptotic (delta method on the log scale).
  Coefficient magnitude;
  /// GM: correlation time (s); SIN: frequency (Hz); unused (NaN bounds) otherwise.
  Coefficient shape;
  /// The optimiser's magnitude, also for a term not identified (whose magnitude.value is 0 by
  /// the convention of every fit): the model that GmwmScale::wv_model and the report's model
  /// curve are. 0 when the fit did not converge (the last iterate is no estimate).
  double magnitude_fitted = 0.0;
  /// GM, SIN: the optimiser's correlation time or frequency, kept likewise (shape.value may be
  /// set to 0 where the term is not identified).
  double shape_fitted = 0.0;
  /// Bootstrap percentile intervals (NaN when not run).
  double magnitude_boot_low = 0.0, magnitude_boot_high = 0.0;
  double shape_boot_low = 0.0, shape_boot_high = 0.0;
  /// BGM: the Gauss-Markov states it stands for (sigma_i = B sqrt(w_i) with B's interval and
  /// verdict; T_i fixed by the mixture), by correlation time.
  std::vector<GaussMarkovTerm> states;
};

/// One candidate of the model selection (or the one requested model).
struct GmwmCandidate {
  std::string model;        ///< e.g. "N+K+GM+GM"
  int parameters = 0;       ///< free parameters
  double objective = 0.0;   ///< (a_hat - a)' W (a_hat - a) at the optimum (W common to the candidates)
  double j_statistic = 0.0; ///< generalised J (header comment), Sigma of the reference model
  std::size_t dof = 0;      ///< scales - free parameters
  double j_p_value = 0.0;   ///< chi^2(dof) upper tail of j_statistic
  double penalty = 0.0;     ///< 2 tr(W Cov(a_hat, a(theta_hat)))
  double wvic = 0.0;        ///< objective + penalty
  bool converged = false;
  bool selected = false;
};

/// The curve at one scale, as Haar wavelet variance (= AVAR / 2), SI.
struct GmwmScale {
  double tau_s = 0.0;
  double wv = 0.0;        ///< measured
  double wv_model = 0.0;  ///< fitted model
  double wv_sd = 0.0;     ///< sd of the estimate under the fitted model
};

enum class GmwmStatus {
  converged,       ///< optimum found, W at the fitted model
  no_convergence,  ///< iteration limit: last iterate, use with care
  too_few_scales,  ///< fewer dyadic scales than parameters + 1: nothing fitted
};
std::string gmwm_status_name(GmwmStatus status);

struct GmwmResult {
  GmwmStatus status = GmwmStatus::too_few_scales;
  std::string message;
  std::string model;  ///< the fitted (selected) model, e.g. "N+K+GM+GM"
  std::vector<GmwmTermEstimate> terms;  ///< in model order, GM terms by correlation time
  double objective = 0.0;  ///< (a_hat - a)' W (a_hat - a), W at the fitted model
  double j_statistic = 0.0;  ///< generalised J (header comment), chi^2(dof) for an exact model
  std::size_t dof = 0;
  double j_p_value = 0.0;
  double wvic = 0.0;
  int iterations = 0;  ///< LM iterations of the final fit
  std::vector<GmwmCandidate> candidates;  ///< the selection table (auto) or the one model
  std::vector<GmwmScale> scales;
  int bootstrap_replicates = 0;  ///< replicates that converged
  std::uint64_t seed = 0;
  /// BGM: the mixture used (empty otherwise).
  FlickerMixture flicker_mixture;
  /// Robust estimates (GmwmOptions::robust): the efficiency used and its biweight constant.
  bool robust = false;
  double robust_efficiency = 1.0;
  double robust_tuning = 0.0;
  std::vector<std::string> warnings;
};

/// Allan variance (SI, 2 x the Haar wavelet variance) of the fitted model at tau = m tau0_s,
/// every term at its fitted magnitude (GmwmTermEstimate::magnitude_fitted, so a term kept in
/// the model but not significant still counts, as in the fit). 0 without a converged fit.
double gmwm_model_avar(const GmwmResult& result, double tau0_s, std::size_t m);

/// The GMWM fit of an overlapping Allan variance curve. m: averaging factors (only powers of
/// two are used: the dyadic scales), avar: the estimates (SI), n_phase phase samples, tau0_s
/// the sample interval. Throws InputError for invalid options or a model with more parameters
/// than the curve has dyadic scales (status too_few_scales is then not used); numerical
/// outcomes are in status. phase_si: the record's phase samples (n_phase of them), needed by
/// options.robust only (the robust estimates replace avar; InputError without them).
GmwmResult fit_gmwm(std::span<const std::size_t> m, std::span<const double> avar,
                    std::size_t n_phase, double tau0_s, const GmwmOptions& options,
                    std::span<const double> phase_si = {});

}  // namespace imunoise::fit
