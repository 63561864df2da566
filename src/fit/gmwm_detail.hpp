#pragma once
// Internals of the GMWM fit shared by gmwm.cpp (model, optimiser), gmwm_fit.cpp (starts,
// weights, selection, intervals), gmwm_profile.cpp (profile intervals), gmwm_near_optima.cpp
// (other optima as good, for the intervals) and gmwm_bootstrap.cpp. Internal to the fit module.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "imunoise/fit/gmwm.hpp"
#include "imunoise/fit/robust_wavelet.hpp"

namespace imunoise::fit::detail {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

/// The dyadic part of the curve, SI Allan variance.
struct GmwmCurve {
  std::vector<std::size_t> m;
  std::vector<double> tau_s;
  std::vector<double> avar;
  std::size_t n_phase = 0;
  double tau0_s = 0.0;
  unsigned threads = 1;  ///< for the covariance sums
  bool full_weight = false;  ///< W = Sigma^-1 (true) or diag(Sigma)^-1 (GmwmOptions::full_weight)
  int max_iterations = 200;  ///< LM iterations per start (GmwmOptions::max_iterations)
  /// BGM: the flicker mixture over this curve's scales (empty without BGM).
  FlickerMixture flicker_mixture;
  /// 1 for the classical estimates; the biweight's efficiency for robust ones (the model
  /// covariance is divided by it).
  double efficiency = 1.0;
  bool robust = false;
  Biweight biweight;  ///< robust: the estimator of the scales (robust_wavelet.hpp)
};

/// Where each term's parameters sit in the parameter vector (log variance, then log T_c or
/// log f0 for GM and SIN).
struct Layout {
  std::vector<GmwmTerm> terms;
  std::vector<Eigen::Index> magnitude;
  std::vector<Eigen::Index> shape;  // -1: none
  Eigen::Index parameters = 0;
  Layout() = default;
  explicit Layout(std::vector<GmwmTerm> kinds);
};

struct Bounds {
  Vector lo, hi;
};

struct LmResult {
  Vector p;
  double cost = 0.0;
  int iterations = 0;
  bool converged = false;
};

std::string model_name(const std::vector<GmwmTerm>& terms);
/// Model Allan variance at every scale; *jacobian (may be null) gets d a / d p.
Vector model_avar(const Layout& layout, const Vector& p, const GmwmCurve& c, Matrix* jacobian);
/// Covariance of the estimates under the model p (GmwmCovarianceBasis).
Matrix model_covariance(const Layout& layout, const Vector& p, const GmwmCurve& c);
/// The square root Wh of the weight W = Wh' Wh: Sigma^-1 (full, Wh Sigma Wh' = I) or
/// diag(Sigma)^-1 (c.full_weight false).
Matrix whitener_of(const Matrix& sigma, const GmwmCurve& c);
/// Non-negative least squares (Lawson-Hanson).
Vector nnls_lh(const Matrix& a, const Vector& b);
Bounds bounds_for(const Layout& layout, const GmwmCurve& c);
/// Projected Levenberg-Marquardt on || whiten (a_hat - a(p)) ||^2 within bounds.
LmResult levenberg_marquardt(const Layout& layout, const GmwmCurve& c, const Matrix& whiten,
                             Vector p, const Bounds& bounds, int max_iterations);

/// The objective a profile interval climbs. `scale_dof` empty: the fit's own, the linear
/// ||Wh (a_hat - a(p))||^2. Otherwise the same quadratic form in each scale's cube-root score
/// (cube_root_score.hpp) times `scale_sd`, with both held at the optimum's values: at the long
/// scales an estimate has a few degrees of freedom and the linear form's rise misjudges a
/// chi-square's skew there, as J's did before the cube-root score (docs/fit.md).
struct ProfileObjective {
  Matrix whiten;
  Vector scale_dof;
  Vector scale_sd;
};
/// The cube-root-score objective at the optimum: whitener wh, each scale's sd and degrees of
/// freedom 2 a^2 / Var from sigma and the model's values `model`.
ProfileObjective score_objective(const Matrix& wh, const Matrix& sigma, const Vector& model);
/// Its local minimum from `from` within `bounds`: LM for the linear objective; for the score
/// objective Gauss-Newton on the scores linearised in a (each step an LM fit of pseudo-data),
/// stopped when the objective stops falling.
LmResult minimise(const ProfileObjective& o, const Layout& layout, const GmwmCurve& c, const Bounds& bounds,
                  const Vector& from);

/// The profile interval of parameter j: the values v for which the objective `o` with p(j) = v
/// and every other parameter refitted (within `bounds`, those of the fit: bounds_for) exceeds
/// `cost` (the objective at p, the optimum) by at most `rise`; found by doubling steps from p(j)
/// (first `step`) and bisection. An end at a bound is returned as that bound.
std::pair<double, double> profile_interval(const Layout& layout, const GmwmCurve& c, const ProfileObjective& o,
                                           const Bounds& bounds, const Vector& p, double cost, Eigen::Index j,
                                           double rise, double step);

/// Parameters stuck at their lower bound (the objective does not want the term): each magnitude
/// within 6 log units of its floor, and that term's shape with it.
std::vector<bool> at_floor(const Layout& layout, const Vector& p, const Bounds& b);

/// Sets p's magnitudes (log variances) to the weighted NNLS solution at p's shapes, a term
/// NNLS drops to a small value above its floor; returns the NNLS cost.
double magnitudes_by_nnls(const Layout& layout, const GmwmCurve& c, const Matrix& whiten, const Bounds& bounds,
                          Vector& p);

/// Correlation times a decade apart (from 10^offset times a power of ten) over the curve's span:
/// from half the shortest tau's Gauss-Markov peak to the longest's.
std::vector<double> tc_decade_grid(const GmwmCurve& c, double offset);

/// A starting point of the multi-start fit and its NNLS cost.
struct Start {
  double cost;
  Vector p;
};
/// The multi-start fit's starting points, least NNLS cost first: T_c / f0 sets from the curve's
/// bumps and from grids a decade apart, each with its variances by NNLS.
std::vector<Start> ranked_starts(const Layout& layout, const GmwmCurve& c, const Matrix& whiten, const Bounds& bounds);
/// Whether two parameter vectors are the same start or optimum: within a factor e^0.3 in every
/// log parameter.
bool same_point(const Vector& a, const Vector& b);

/// A fitted model with a given weight: the best of several starts.
struct ModelFit {
  Layout layout;
  LmResult lm;
  bool ok = false;
};
/// Multi-start fit of `layout` with the whitener `whiten` (starts: NNLS variances for T_c / f0
/// sets from the curve's bumps and from grids a decade apart), warm start `warm` when given.
ModelFit fit_model(const Layout& layout, const GmwmCurve& c, const Matrix& whiten,
                   const Vector* warm = nullptr);

/// Other local optima of the model at the weight `whiten` whose objective exceeds the optimum
/// `best`'s by at most `rise`, at most `count`, least objective first; each with its Gauss-Markov
/// terms relabelled so that they rank by correlation time as best's do (gmwm_near_optima.cpp).
std::vector<LmResult> near_optima(const Layout& layout, const GmwmCurve& c, const Matrix& whiten,
                                  const LmResult& best, double rise, std::size_t count);

/// Parametric bootstrap: `replicates` records simulated from the fitted model p (src/sim),
/// each fitted with the weight `whiten` from p; returns one row of log parameters per
/// converged replicate.
std::vector<Vector> bootstrap_parameters(const Layout& layout, const Vector& p, const GmwmCurve& c,
                                         const Matrix& whiten, int replicates, std::uint64_t seed,
                                         unsigned threads);

}  // namespace imunoise::fit::detail
