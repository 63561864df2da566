// GMWM: starting values, iterated weights, WVIC selection and intervals (gmwm.hpp).
#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/gmwm.hpp"
#include "gmwm_detail.hpp"
#include "cube_root_score.hpp"
#include "least_squares.hpp"

namespace imunoise::fit {
namespace detail {
namespace {

constexpr std::size_t kStartsKept = 3;
constexpr double kGmPeakRatio = 1.89262;  // tau of the Gauss-Markov Allan peak / T_c

/// Every sorted choice of `count` values from `values`.
void choose(const std::vector<double>& values, std::size_t count, std::size_t from,
            std::vector<double>& current, std::vector<std::vector<double>>& out) {
  if (current.size() == count) {
    out.push_back(current);
    return;
  }
  for (std::size_t i = from; i < values.size(); ++i) {
    if (values.size() - i < count - current.size()) break;
    current.push_back(values[i]);
    choose(values, count, i + 1, current, out);
    current.pop_back();
  }
}

/// Taus of the curve's concave bends (local bumps): log-log slope of the Allan variance falling.
std::vector<double> bump_taus(const GmwmCurve& c) {
  std::vector<double> out;
  for (std::size_t i = 1; i + 1 < c.tau_s.size(); ++i) {
    const double s1 = std::log(c.avar[i] / c.avar[i - 1]) / std::log(c.tau_s[i] / c.tau_s[i - 1]);
    const double s2 = std::log(c.avar[i + 1] / c.avar[i]) / std::log(c.tau_s[i + 1] / c.tau_s[i]);
    if (s2 < s1 - 0.1) out.push_back(c.tau_s[i]);
  }
  return out;
}

/// The best optimum of a fit continued from its last iterate (fresh damping) while it stops at
/// the iteration limit, at most kContinuations times: in a long flat valley LM keeps
/// improving past the limit. Only the best start gets the extra budget (two records of 200 in
/// the 3 h two-AR1 study needed 431 and 747 iterations and were reported not converged, every
/// term not identified; docs/fit.md).
LmResult continue_to_convergence(const Layout& layout, const GmwmCurve& c, const Matrix& whiten, LmResult lm,
                                 const Bounds& bounds) {
  constexpr int kContinuations = 9;
  for (int more = 0; more < kContinuations && !lm.converged; ++more) {
    LmResult next = levenberg_marquardt(layout, c, whiten, lm.p, bounds, c.max_iterations);
    if (!(std::isfinite(next.cost) && next.cost <= lm.cost)) break;
    next.iterations += lm.iterations;
    lm = std::move(next);
  }
  return lm;
}

}  // namespace

double magnitudes_by_nnls(const Layout& layout, const GmwmCurve& c, const Matrix& whiten, const Bounds& bounds,
                          Vector& p) {
  const auto k = static_cast<Eigen::Index>(c.tau_s.size());
  const Vector b = whiten * Eigen::Map<const Vector>(c.avar.data(), k);
  // The model is linear in the variances: each term's unit column evaluates the whole model
  // with the other terms at a negligible magnitude.
  Matrix g(k, static_cast<Eigen::Index>(layout.terms.size()));
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    Vector unit = p;
    for (std::size_t u = 0; u < layout.terms.size(); ++u) unit(layout.magnitude[u]) = u == t ? 0.0 : -700.0;
    g.col(static_cast<Eigen::Index>(t)) = model_avar(layout, unit, c, nullptr);
  }
  const Vector x = nnls_lh(whiten * g, b);
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const Eigen::Index j = layout.magnitude[t];
    // A term NNLS drops starts small but above its floor: at the floor the log-variance has no
    // gradient, and LM could never bring the term back.
    const double small = bounds.hi(j) - 2.0 - 12.0;  // 6e-6 of the upper bound
    const double v = x(static_cast<Eigen::Index>(t));
    p(j) = std::clamp(v > 0.0 ? std::log(v) : small, bounds.lo(j), bounds.hi(j));
  }
  return (whiten * g * x - b).squaredNorm();
}

std::vector<double> tc_decade_grid(const GmwmCurve& c, double offset) {
  const double tc_lo = c.tau_s.front() / kGmPeakRatio / 2.0, tc_hi = c.tau_s.back() / kGmPeakRatio;
  std::vector<double> out;
  for (double e = std::floor(std::log10(tc_lo)) + offset; e <= std::log10(tc_hi) + 1e-9; e += 1.0) {
    const double t = std::pow(10.0, e);
    if (t >= tc_lo) out.push_back(t);
  }
  return out;
}

std::vector<Start> ranked_starts(const Layout& layout, const GmwmCurve& c, const Matrix& whiten, const Bounds& bounds) {
  std::vector<std::size_t> gm, sin;
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    if (layout.terms[t] == GmwmTerm::GM) gm.push_back(t);
    if (layout.terms[t] == GmwmTerm::SIN) sin.push_back(t);
  }
  // Shape candidates: T_c on two grids a decade apart (offset by half a decade) over the
  // curve's span, and the bumps; f0 from the bumps and a decade grid.
  const double tc_lo = c.tau_s.front() / kGmPeakRatio / 2.0, tc_hi = c.tau_s.back() / kGmPeakRatio;
  std::vector<std::vector<double>> tc_grids{tc_decade_grid(c, 0.0), tc_decade_grid(c, 0.5), {}};
  for (double tau : bump_taus(c)) tc_grids[2].push_back(tau / kGmPeakRatio);
  std::vector<std::vector<double>> tc_sets;
  if (gm.empty()) {
    tc_sets.push_back({});
  } else {
    for (auto& grid : tc_grids) {
      // The bump list is completed by the decade grid so that every GM term has a start.
      std::vector<double> values = grid;
      if (&grid == &tc_grids[2]) {
        for (double t : tc_grids[0]) {
          if (std::none_of(values.begin(), values.end(), [&](double v) { return std::abs(std::log10(v / t)) < 0.5; })) {
            values.push_back(t);
          }
        }
        std::sort(values.begin(), values.end());
      }
      if (values.size() < gm.size()) {
        // Too few grid points for the GM terms: spread them evenly in log over the span.
        values.clear();
        for (std::size_t g = 0; g < gm.size(); ++g) {
          values.push_back(tc_lo * std::pow(tc_hi / tc_lo, (static_cast<double>(g) + 0.5) / static_cast<double>(gm.size())));
        }
      }
      std::vector<double> current;
      choose(values, gm.size(), 0, current, tc_sets);
    }
  }
  std::vector<double> f_values{0.0};
  if (!sin.empty()) {
    f_values.clear();
    for (double tau : bump_taus(c)) f_values.push_back(0.371 / tau);
    for (double tau = c.tau_s.front(); tau <= c.tau_s.back(); tau *= 8.0) f_values.push_back(0.371 / tau);
  }
  std::vector<Start> starts;
  for (const auto& tcs : tc_sets) {
    for (double f0 : f_values) {
      // Every shape first (magnitudes_by_nnls evaluates the whole model).
      Vector p = Vector::Zero(layout.parameters);
      for (std::size_t t = 0, gi = 0; t < layout.terms.size(); ++t) {
        double shape = 0.0;
        if (layout.terms[t] == GmwmTerm::GM) shape = tcs[gi++];
        if (layout.terms[t] == GmwmTerm::SIN) shape = f0;
        if (layout.shape[t] >= 0) p(layout.shape[t]) = std::clamp(std::log(shape), bounds.lo(layout.shape[t]), bounds.hi(layout.shape[t]));
      }
      const double cost = magnitudes_by_nnls(layout, c, whiten, bounds, p);
      starts.push_back({cost, p});
    }
  }
  std::sort(starts.begin(), starts.end(), [](const Start& a, const Start& b2) { return a.cost < b2.cost; });
  return starts;
}

bool same_point(const Vector& a, const Vector& b) { return (a - b).cwiseAbs().maxCoeff() < 0.3; }

ModelFit fit_model(const Layout& layout, const GmwmCurve& c, const Matrix& whiten, const Vector* warm) {
  const Bounds bounds = bounds_for(layout, c);
  const std::vector<Start> starts = ranked_starts(layout, c, whiten, bounds);
  ModelFit best;
  best.layout = layout;
  best.lm.cost = std::numeric_limits<double>::infinity();
  std::vector<Vector> tried;
  auto run = [&](const Vector& p0) {
    LmResult r = levenberg_marquardt(layout, c, whiten, p0, bounds, c.max_iterations);
    if (std::isfinite(r.cost) && r.cost < best.lm.cost) {
      best.lm = std::move(r);
      best.ok = true;
    }
  };
  if (warm != nullptr) run(*warm);
  std::size_t used = 0;
  for (const auto& s : starts) {
    if (used >= kStartsKept) break;
    // Skip starts that are the same point as one already run.
    if (std::any_of(tried.begin(), tried.end(), [&](const Vector& t) { return same_point(t, s.p); })) continue;
    tried.push_back(s.p);
    run(s.p);
    ++used;
  }
  if (best.ok) best.lm = continue_to_convergence(layout, c, whiten, std::move(best.lm), bounds);
  return best;
}

namespace {

double chi2_upper(double x, std::size_t dof) {
  if (dof == 0) return std::numeric_limits<double>::quiet_NaN();
  const boost::math::chi_squared_distribution<double> d(static_cast<double>(dof));
  return boost::math::cdf(boost::math::complement(d, std::max(0.0, x)));
}

}  // namespace

std::vector<bool> at_floor(const Layout& layout, const Vector& p, const Bounds& b) {
  std::vector<bool> out(static_cast<std::size_t>(layout.parameters), false);
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const Eigen::Index j = layout.magnitude[t];
    if (p(j) < b.lo(j) + 6.0) {
      out[static_cast<std::size_t>(j)] = true;
      if (layout.shape[t] >= 0) out[static_cast<std::size_t>(layout.shape[t])] = true;
    }
  }
  return out;
}

namespace {

/// The generalised J statistic and its degrees of freedom (gmwm.hpp): e' C^+ e with C the
/// covariance of the whitened residual e under the model, rank k - p.
std::pair<double, std::size_t> j_test(const Vector& e, const Matrix& dw_all, const Matrix& s,
                                      const std::vector<bool>& fixed) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index j = 0; j < dw_all.cols(); ++j) {
    if (!fixed[static_cast<std::size_t>(j)]) free.push_back(j);
  }
  const Eigen::Index k = e.size();
  Matrix p = Matrix::Zero(k, k);
  if (!free.empty()) {
    Matrix dw(k, static_cast<Eigen::Index>(free.size()));
    for (std::size_t f = 0; f < free.size(); ++f) dw.col(static_cast<Eigen::Index>(f)) = dw_all.col(free[f]);
    p = dw * (dw.transpose() * dw).completeOrthogonalDecomposition().pseudoInverse() * dw.transpose();
  }
  const Matrix q = Matrix::Identity(k, k) - p;
  const Matrix cr = q * s * q.transpose();
  const Eigen::SelfAdjointEigenSolver<Matrix> es(0.5 * (cr + cr.transpose()));
  const double top = es.eigenvalues().maxCoeff();
  // The projector removes p directions exactly: keep the k - p largest eigenvalues.
  const auto rank = static_cast<Eigen::Index>(std::max<std::ptrdiff_t>(0, k - static_cast<Eigen::Index>(free.size())));
  double j = 0.0;
  for (Eigen::Index i = k - rank; i < k; ++i) {
    const double lambda = es.eigenvalues()(i);
    if (!(lambda > 1e-14 * top)) continue;
    const double proj = es.eigenvectors().col(i).dot(e);
    j += proj * proj / lambda;
  }
  return {j, static_cast<std::size_t>(rank)};
}

/// Sandwich covariance of the log parameters: A S A' with A = (Dw' Dw)^-1 Dw' (whitened), on
/// the free parameters (others: infinite variance).
Matrix log_covariance(const Matrix& dw, const Matrix& s, const std::vector<bool>& fixed) {
  const Eigen::Index n = dw.cols();
  std::vector<Eigen::Index> free;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!fixed[static_cast<std::size_t>(j)]) free.push_back(j);
  }
  Matrix cov = Matrix::Constant(n, n, 0.0);
  for (Eigen::Index j = 0; j < n; ++j) cov(j, j) = std::numeric_limits<double>::infinity();
  if (free.empty()) return cov;
  Matrix sub(dw.rows(), static_cast<Eigen::Index>(free.size()));
  for (std::size_t f = 0; f < free.size(); ++f) sub.col(static_cast<Eigen::Index>(f)) = dw.col(free[f]);
  const Matrix info = sub.transpose() * sub;
  const Eigen::CompleteOrthogonalDecomposition<Matrix> cod(info);
  const Matrix a_mat = cod.pseudoInverse() * sub.transpose();
  const Matrix inv = a_mat * s * a_mat.transpose();
  for (std::size_t a = 0; a < free.size(); ++a) {
    for (std::size_t b = 0; b < free.size(); ++b) {
      cov(free[a], free[b]) = inv(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    }
  }
  // A direction the data do not determine (rank-deficient information) gets infinite variance.
  if (cod.rank() < static_cast<Eigen::Index>(free.size())) {
    const Eigen::SelfAdjointEigenSolver<Matrix> es(info);
    for (Eigen::Index e = 0; e < es.eigenvalues().size(); ++e) {
      if (es.eigenvalues()(e) <= 1e-12 * es.eigenvalues().maxCoeff()) {
        for (std::size_t a = 0; a < free.size(); ++a) {
          if (std::abs(es.eigenvectors()(static_cast<Eigen::Index>(a), e)) > 0.1) {
            cov(free[a], free[a]) = std::numeric_limits<double>::infinity();
          }
        }
      }
    }
  }
  return cov;
}

/// 2 tr(W Sigma_c W D (D' W D)^+ D'), with W = Wh' Wh.
double wvic_penalty(const Matrix& wh, const Matrix& sigma_c, const Matrix& d, const std::vector<bool>& fixed) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index j = 0; j < d.cols(); ++j) {
    if (!fixed[static_cast<std::size_t>(j)]) free.push_back(j);
  }
  if (free.empty()) return 0.0;
  Matrix dw(wh.rows(), static_cast<Eigen::Index>(free.size()));
  for (std::size_t f = 0; f < free.size(); ++f) dw.col(static_cast<Eigen::Index>(f)) = wh * d.col(free[f]);
  const Matrix info = dw.transpose() * dw;
  const Matrix inv = info.completeOrthogonalDecomposition().pseudoInverse();
  // tr(Wh Sigma_c Wh' * Dw inv Dw') (cyclic: W Sigma W D inv D' = Wh' [Wh Sigma Wh'] Dw inv Dw' Wh).
  const Matrix s = wh * sigma_c * wh.transpose();
  return 2.0 * (s * dw * inv * dw.transpose()).trace();
}

struct Weighted {
  ModelFit fit;
  Matrix whiten;
  Matrix sigma;
  int weight_passes = 0;
};

/// The covariance of the wavelet variances for the intervals: sigma (the model's at p, where its
/// wavelet variances are a_fit) with each scale's row and column rescaled by a_j(p_-j) / a_j(p),
/// where p_-j is p refitted without scale j (at the fitted weight less that scale). Why: at p a record whose long scales happen
/// to be low has a small K, hence a small variance at those scales and an interval narrowest
/// when K is lowest (docs/fit.md, the 200-record study: K covered 174 of 200); a scale's
/// variance from a fit that did not see its own estimate does not shrink with it (185 of 200).
Matrix leave_one_scale_out_covariance(const Layout& layout, const GmwmCurve& c, const Vector& p,
                                      const Vector& a_fit, const Matrix& sigma) {
  const Eigen::Index k = sigma.rows();
  Vector scale = Vector::Ones(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    GmwmCurve rest = c;
    rest.m.erase(rest.m.begin() + j);
    rest.tau_s.erase(rest.tau_s.begin() + j);
    rest.avar.erase(rest.avar.begin() + j);
    std::vector<Eigen::Index> keep;
    for (Eigen::Index i = 0; i < k; ++i) {
      if (i != j) keep.push_back(i);
    }
    const Matrix sigma_rest = sigma(keep, keep);
    const LmResult refit = levenberg_marquardt(layout, rest, whitener_of(sigma_rest, rest), p,
                                               bounds_for(layout, rest), c.max_iterations);
    const double a_rest = model_avar(layout, refit.p, c, nullptr)(j);
    if (a_rest > 0.0 && a_fit(j) > 0.0 && std::isfinite(a_rest)) scale(j) = a_rest / a_fit(j);
  }
  return scale.asDiagonal() * sigma * scale.asDiagonal();
}

/// The covariance of the wavelet variances under the model p, its whitener, and the objective
/// of p at that weight (its own weight).
struct OwnWeight {
  Matrix sigma;
  Matrix whiten;
  double cost = 0.0;
};
OwnWeight at_own_weight(const Layout& layout, const GmwmCurve& c, const Vector& p) {
  OwnWeight o;
  o.sigma = model_covariance(layout, p, c);
  o.whiten = whitener_of(o.sigma, c);
  const Vector y = Eigen::Map<const Vector>(c.avar.data(), static_cast<Eigen::Index>(c.avar.size()));
  o.cost = (o.whiten * (y - model_avar(layout, p, c, nullptr))).squaredNorm();
  return o;
}

/// The J statistic of the model p and its degrees of freedom, with sigma the covariance of the
/// wavelet variances and wh the whitener of the weight (the cube-root-score residual, j_test).
std::pair<double, std::size_t> j_of(const Layout& layout, const GmwmCurve& c, const Vector& p, const Matrix& sigma,
                                    const Matrix& wh) {
  Matrix d;
  const Vector model = model_avar(layout, p, c, &d);
  const Vector e = wh * cube_root_score_residual(c.avar, model, sigma);
  const auto fixed = at_floor(layout, p, bounds_for(layout, c));
  return j_test(e, wh * d, wh * sigma * wh.transpose(), fixed);
}

/// The J statistic of p at its own weight o, as fit_gmwm reports it.
double own_j(const Layout& layout, const GmwmCurve& c, const Vector& p, const OwnWeight& o) {
  return j_of(layout, c, p, o.sigma, o.whiten).first;
}

/// p carried to a fixed point of the weight iteration by local refits only (LM from p at the
/// weight of p, repeated until p stops moving or `passes` are spent).
LmResult local_fixed_point(const Layout& layout, const GmwmCurve& c, LmResult lm, int passes) {
  const Bounds bounds = bounds_for(layout, c);
  for (int pass = 0; pass < passes; ++pass) {
    const OwnWeight o = at_own_weight(layout, c, lm.p);
    LmResult next = continue_to_convergence(
        layout, c, o.whiten, levenberg_marquardt(layout, c, o.whiten, lm.p, bounds, c.max_iterations), bounds);
    if (!std::isfinite(next.cost)) break;
    const double move = (next.p - lm.p).cwiseAbs().maxCoeff();
    lm = std::move(next);
    if (move < 1e-4) break;
  }
  return lm;
}

/// The end of a weight iteration that cycled (see iterate_weights): each optimum it visited
/// carried to its own fixed point; among those that are proper (the starts find nothing
/// better at the point's own weight) the one with the least J replaces `last`, the last
/// iterate, when its J is less than last's. J, not the objective: at its own weight a model
/// that overstates the variances lowers its objective by that alone (one record of 200 ran to
/// a GM term 45 sd from the truth when the objective chose).
LmResult settle_cycle(const Layout& layout, const GmwmCurve& c, const std::vector<LmResult>& visited, LmResult last) {
  constexpr int kLocalPasses = 10;
  double best = own_j(layout, c, last.p, at_own_weight(layout, c, last.p));
  // A fixed point counts only if its last refit converged (three-AR1 record 74: one that did
  // not had the least J, and the whole fit was then reported as not converged, every term not
  // identified). And J counts a term at its floor as fixed (one degree of freedom fewer), so the
  // J of a description with more terms at their floors is not comparable to last's.
  const Bounds bounds = bounds_for(layout, c);
  auto floors = [&](const Vector& p) {
    const auto flags = at_floor(layout, p, bounds);
    return std::count(flags.begin(), flags.end(), true);
  };
  const auto last_floors = floors(last.p);
  std::vector<Vector> done;
  for (const LmResult& v : visited) {
    // Optima within a factor 1.6 in every parameter reach the same fixed point: polished once.
    if (std::any_of(done.begin(), done.end(), [&](const Vector& d) { return (d - v.p).cwiseAbs().maxCoeff() < 0.5; })) {
      continue;
    }
    done.push_back(v.p);
    LmResult fixed = local_fixed_point(layout, c, v, kLocalPasses);
    if (!fixed.converged || floors(fixed.p) > last_floors) continue;
    const OwnWeight own = at_own_weight(layout, c, fixed.p);
    const ModelFit check = fit_model(layout, c, own.whiten, &fixed.p);
    if (check.ok && check.lm.cost < own.cost - 1e-3 * std::max(1.0, own.cost)) continue;
    const double j = own_j(layout, c, fixed.p, own);
    if (j < best) {
      best = j;
      last = std::move(fixed);
    }
  }
  return last;
}

/// Fit with W iterated at the fitted model: W0 given, then `passes` recomputations, each a
/// multi-start fit. Should the last pass still move p by more than a few percent, the iteration
/// is cycling between two descriptions of the curve (on two-GM records, K against a long-T_c GM
/// term carrying the random walk: each one's weight favours the other) and the last iterate
/// is neither's optimum: settle_cycle.
Weighted iterate_weights(const Layout& layout, const GmwmCurve& c, const Matrix& whiten0, int passes) {
  Weighted w;
  w.fit = fit_model(layout, c, whiten0);
  w.whiten = whiten0;
  std::vector<LmResult> visited;
  if (w.fit.ok) visited.push_back(w.fit.lm);
  double last_move = 0.0;
  for (int pass = 0; pass < passes && w.fit.ok; ++pass) {
    OwnWeight own = at_own_weight(layout, c, w.fit.lm.p);
    w.sigma = std::move(own.sigma);
    w.whiten = std::move(own.whiten);
    const Vector warm = w.fit.lm.p;
    // From the previous optimum and from the starts (the weight changed).
    ModelFit next = fit_model(layout, c, w.whiten, &warm);
    last_move = next.ok ? (next.lm.p - warm).cwiseAbs().maxCoeff() : 0.0;
    if (next.ok) {
      w.fit = std::move(next);
      visited.push_back(w.fit.lm);
    }
    ++w.weight_passes;
    if (last_move < 1e-4) break;
  }
  if (!w.fit.ok) return w;
  // A last step of a few percent is convergence still under way, not a cycle; one pass (the
  // selection's common weight) cannot tell the two apart and is left as it is.
  constexpr double kCycling = 0.05;
  if (passes >= 2 && last_move > kCycling) w.fit.lm = settle_cycle(layout, c, visited, std::move(w.fit.lm));
  // The final covariance at the final parameters (J with W at the fitted model).
  OwnWeight o = at_own_weight(layout, c, w.fit.lm.p);
  w.sigma = std::move(o.sigma);
  w.whiten = std::move(o.whiten);
  w.fit.lm.cost = o.cost;
  return w;
}

/// The first weight: the covariance under a power-law model (Q, N, B, K, R by NNLS with the
/// curve's own rough sampling variance 2 a^2 m / (n_phase - 2m)).
Matrix initial_whitener(const GmwmCurve& c) {
  const auto k = static_cast<Eigen::Index>(c.tau_s.size());
  Matrix g(k, kTermCount);
  Vector y(k), w(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    g(i, kQ) = gmwm_avar_quantization(c.tau_s[ii]);
    g(i, kN) = gmwm_avar_white(c.tau_s[ii]);
    g(i, kB) = gmwm_avar_flicker(c.tau_s[ii]);
    g(i, kK) = gmwm_avar_random_walk(c.tau_s[ii]);
    g(i, kR) = gmwm_avar_ramp(c.tau_s[ii]);
    y(i) = c.avar[ii];
    const double edf = std::max(1.0, static_cast<double>(c.n_phase - 2 * c.m[ii]) / static_cast<double>(c.m[ii]));
    w(i) = 1.0 / (c.avar[ii] * std::sqrt(2.0 / edf));
  }
  const Vector theta = nnls_lh(w.asDiagonal() * g, w.asDiagonal() * y);
  double t5[kTermCount];
  for (int j = 0; j < kTermCount; ++j) t5[j] = theta(j);
  const GmwmCovarianceBasis basis(c.m, c.n_phase, c.tau0_s, {}, theta(kB) > 0.0, c.threads);
  return whitener_of(to_matrix(basis.covariance(t5, {}), c.m.size()), c);
}

// Every candidate: white noise, then 0..max_gm GM terms, each with and without K, and (when
// asked) each again with one sinusoid: real sensors' curves carry bumps (a vibration, a
// thermal cycle) that no sum of Gauss-Markov terms follows (docs/fit.md, unit 2's gyro z).
std::vector<std::vector<GmwmTerm>> auto_candidates(int max_gm, bool with_sinusoid) {
  std::vector<std::vector<GmwmTerm>> out;
  for (int with_sin = 0; with_sin < (with_sinusoid ? 2 : 1); ++with_sin) {
    for (int g = 0; g <= max_gm; ++g) {
      for (int with_k = 0; with_k < 2; ++with_k) {
        std::vector<GmwmTerm> t{GmwmTerm::N};
        if (with_k) t.push_back(GmwmTerm::K);
        for (int i = 0; i < g; ++i) t.push_back(GmwmTerm::GM);
        if (with_sin) t.push_back(GmwmTerm::SIN);
        out.push_back(t);
      }
    }
  }
  return out;
}

}  // namespace
}  // namespace detail

namespace {
double detail_normal_quantile(double level) {
  const boost::math::normal_distribution<double> normal;
  return boost::math::quantile(normal, 0.5 + 0.5 * level);
}
}  // namespace

GmwmResult fit_gmwm(std::span<const std::size_t> m, std::span<const double> avar, std::size_t n_phase,
                    double tau0_s, const GmwmOptions& options, std::span<const double> phase_si) {
  using namespace detail;
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (m.size() != avar.size()) throw InputError("gmwm: m and avar differ in length");
  if (!(tau0_s > 0.0)) throw InputError("gmwm: tau0 must be positive");
  GmwmCurve c;
  c.n_phase = n_phase;
  c.tau0_s = tau0_s;
  c.threads = options.threads;
  c.full_weight = options.full_weight;
  c.max_iterations = options.max_iterations;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const bool dyadic = m[i] > 0 && (m[i] & (m[i] - 1)) == 0;
    if (dyadic && avar[i] > 0.0 && std::isfinite(avar[i]) && n_phase > 2 * m[i]) {
      c.m.push_back(m[i]);
      c.tau_s.push_back(static_cast<double>(m[i]) * tau0_s);
      c.avar.push_back(avar[i]);
    }
  }
  GmwmResult result;
  result.seed = options.seed;
  if (options.robust) {
    // The robust estimates need the samples, not the curve.
    if (phase_si.size() != n_phase) {
      throw InputError(fmt::format("gmwm --robust needs the record's {} phase samples (got {}): the robust "
                                   "wavelet variance is computed from the samples, not from the Allan curve",
                                   n_phase, phase_si.size()));
    }
    c.robust = true;
    c.biweight = biweight_for_efficiency(options.robust_efficiency);
    c.efficiency = c.biweight.efficiency;
    const std::vector<double> r = robust_avar(phase_si, tau0_s, c.m, c.biweight);
    GmwmCurve kept = c;
    kept.m.clear();
    kept.tau_s.clear();
    kept.avar.clear();
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (r[i] > 0.0 && std::isfinite(r[i])) {
        kept.m.push_back(c.m[i]);
        kept.tau_s.push_back(c.tau_s[i]);
        kept.avar.push_back(r[i]);
      }
    }
    if (kept.m.size() < c.m.size()) {
      result.warnings.push_back(fmt::format(
          "gmwm --robust: {} scale(s) left out: more than half of their wavelet coefficients are exactly 0 "
          "(quantized data), so their robust scale is 0",
          c.m.size() - kept.m.size()));
    }
    c = std::move(kept);
    result.robust = true;
    result.robust_efficiency = c.biweight.efficiency;
    result.robust_tuning = c.biweight.c;
  }
  const auto k = c.m.size();
  if (k < m.size()) {
    result.warnings.push_back(fmt::format(
        "gmwm uses the dyadic scales (m = 2^j) of the curve: {} of its {} taus", k, m.size()));
  }

  // The candidates (or the one requested model) that the curve can carry.
  std::vector<std::vector<GmwmTerm>> candidates;
  if (options.automatic) {
    for (auto& t : auto_candidates(options.max_gm, options.auto_sinusoid)) {
      if (static_cast<std::size_t>(Layout(t).parameters) < k) candidates.push_back(t);
    }
    if (candidates.empty()) {
      throw InputError(fmt::format(
          "gmwm --terms auto: the curve has {} dyadic scale(s), too few for any candidate model (the "
          "smallest, N, needs 2); fix: a longer record, a wider --tau-min/--tau-max or --method wls",
          k));
    }
  } else {
    std::vector<GmwmTerm> terms = options.terms;
    const Layout layout(terms);
    if (static_cast<std::size_t>(layout.parameters) >= k) {
      throw InputError(fmt::format(
          "gmwm: the model {} has {} parameters but the curve has only {} dyadic scales (it needs "
          "at least {}); use fewer terms, an octave tau grid or a longer record",
          model_name(terms), layout.parameters, k, layout.parameters + 1));
    }
    candidates.push_back(terms);
    if (std::find(terms.begin(), terms.end(), GmwmTerm::BGM) != terms.end()) {
      // Flat over the scales fitted (gmwm_flicker.hpp).
      c.flicker_mixture = flicker_ar1_mixture(tau0_s, c.m.front(), c.m.back(), options.flicker_states_per_decade);
      result.flicker_mixture = c.flicker_mixture;
    }
  }

  const Matrix w0 = initial_whitener(c);
  std::vector<GmwmTerm> chosen = candidates.front();
  std::vector<std::size_t> ranking;  // auto: candidate indices by WVIC, best first
  if (candidates.size() > 1) {
    // One weight for every candidate: W at the fitted largest candidate (the most flexible
    // description of the curve), so the objectives are comparable.
    std::size_t largest = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (Layout(candidates[i]).parameters > Layout(candidates[largest]).parameters) largest = i;
    }
    const Weighted ref = iterate_weights(Layout(candidates[largest]), c, w0, 1);
    const Matrix wh = ref.fit.ok ? ref.whiten : w0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const Layout layout(candidates[i]);
      const ModelFit f = fit_model(layout, c, wh);
      GmwmCandidate cand;
      cand.model = model_name(candidates[i]);
      cand.parameters = static_cast<int>(layout.parameters);
      cand.dof = k - static_cast<std::size_t>(layout.parameters);
      if (f.ok) {
        Matrix d;
        model_avar(layout, f.lm.p, c, &d);
        const auto fixed = at_floor(layout, f.lm.p, bounds_for(layout, c));
        // Cov(a_hat, a(theta_hat)) under the distribution of the reference model (the most
        // flexible description of the curve): with W = Sigma_ref^-1 the trace is the number of
        // parameters the data determine (a term at its floor or a rank-deficient direction
        // counts 0), docs/fit.md.
        const Matrix sigma_ref = ref.fit.ok ? ref.sigma : Matrix(wh.inverse() * wh.inverse().transpose());
        const auto [j, dof] = j_of(layout, c, f.lm.p, sigma_ref, wh);
        cand.converged = f.lm.converged;
        cand.objective = f.lm.cost;
        cand.j_statistic = j;
        cand.dof = dof;
        cand.j_p_value = chi2_upper(j, dof);
        cand.penalty = wvic_penalty(wh, sigma_ref, d, fixed);
        // A sinusoid's frequency is the best of about k resolvable ones (one per dyadic scale),
        // which the trace above does not count: under white noise the largest of k chi^2(2)
        // drops exceeds x with probability ~ k exp(-x / 2), so 2 ln(20 k) more holds a
        // spurious sinusoid to ~5 % before the trace's own share (without it white noise took
        // one, CliGmwm.BadInput...; docs/fit.md has the measured rates).
        if (std::count(candidates[i].begin(), candidates[i].end(), GmwmTerm::SIN) > 0) {
          cand.penalty += 2.0 * std::log(20.0 * static_cast<double>(k));
        }
        cand.wvic = cand.objective + cand.penalty;
      } else {
        cand.wvic = std::numeric_limits<double>::infinity();
      }
      result.candidates.push_back(cand);
    }
    // Ranked by WVIC among the converged candidates only: the criterion of a last iterate is
    // no estimate's (on other ADIS16405 units an unconverged N+K+GM+GM+GM had the least WVIC
    // and then reported nothing). Strictly better only: a larger candidate whose extra terms
    // ran to their floor ties with the smaller one it reduces to, and the smaller one is kept.
    for (std::size_t i = 0; i < result.candidates.size(); ++i) {
      if (result.candidates[i].converged) ranking.push_back(i);
    }
    if (ranking.empty()) {
      for (std::size_t i = 0; i < result.candidates.size(); ++i) ranking.push_back(i);
    }
    std::size_t best = ranking.front();
    for (const std::size_t i : ranking) {
      const double w = result.candidates[i].wvic, b = result.candidates[best].wvic;
      if (!std::isfinite(b) || w < b - 1e-6 * std::abs(b)) best = i;
    }
    // The others as fallbacks, by WVIC.
    std::erase(ranking, best);
    std::stable_sort(ranking.begin(), ranking.end(), [&](std::size_t a, std::size_t b) {
      return result.candidates[a].wvic < result.candidates[b].wvic;
    });
    ranking.insert(ranking.begin(), best);
    chosen = candidates[best];
  }

  // The chosen model refitted at its own weight; should that fit not converge, the next
  // candidates by WVIC are tried (at most kRefitTries in all), and the warning says so.
  constexpr std::size_t kRefitTries = 3;
  Weighted fin = iterate_weights(Layout(chosen), c, w0, options.weight_iterations);
  std::size_t used_rank = 0;
  for (std::size_t r = 1; r < std::min(ranking.size(), kRefitTries) && !(fin.fit.ok && fin.fit.lm.converged); ++r) {
    Weighted next = iterate_weights(Layout(candidates[ranking[r]]), c, w0, options.weight_iterations);
    if (next.fit.ok && next.fit.lm.converged) {
      result.warnings.push_back(fmt::format(
          "gmwm: the least-WVIC model {} did not converge when refitted at its own weight; the next by WVIC, "
          "{}, is reported",
          model_name(chosen), model_name(candidates[ranking[r]])));
      chosen = candidates[ranking[r]];
      fin = std::move(next);
      used_rank = r;
    }
  }
  if (!ranking.empty()) result.candidates[ranking[used_rank]].selected = true;
  const Layout layout(chosen);
  result.model = model_name(chosen);
  if (!fin.fit.ok) {
    result.status = GmwmStatus::no_convergence;
    result.message = "the optimiser found no finite objective from any start";
    return result;
  }
  const LmResult& lm = fin.fit.lm;
  result.iterations = lm.iterations;
  result.status = lm.converged ? GmwmStatus::converged : GmwmStatus::no_convergence;
  result.message = lm.converged ? fmt::format("converged after {} iterations ({} weight passes)", lm.iterations,
                                              fin.weight_passes)
                                : fmt::format("no convergence in {} iterations: last iterate", lm.iterations);
  Matrix d;
  const Vector model = model_avar(layout, lm.p, c, &d);
  const Bounds bounds = bounds_for(layout, c);
  const auto fixed = at_floor(layout, lm.p, bounds);
  {
    const auto [j, dof] = j_of(layout, c, lm.p, fin.sigma, fin.whiten);
    result.j_statistic = j;
    result.dof = dof;
    result.j_p_value = chi2_upper(j, dof);
  }
  result.objective = lm.cost;
  result.wvic = lm.cost + wvic_penalty(fin.whiten, fin.sigma, d, fixed);
  if (!options.automatic) {
    GmwmCandidate cand;
    cand.model = result.model;
    cand.parameters = static_cast<int>(layout.parameters);
    cand.dof = result.dof;
    cand.j_statistic = result.j_statistic;
    cand.j_p_value = result.j_p_value;
    cand.objective = result.objective;
    cand.wvic = result.wvic;
    cand.penalty = result.wvic - result.objective;
    cand.converged = lm.converged;
    cand.selected = true;
    result.candidates.push_back(cand);
  }
  for (std::size_t i = 0; i < k; ++i) {
    result.scales.push_back({c.tau_s[i], 0.5 * c.avar[i], 0.5 * model(static_cast<Eigen::Index>(i)),
                             0.5 * std::sqrt(fin.sigma(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)))});
  }

  // Intervals: delta method on the log scale, W at the fitted model, the estimates' covariance
  // with each scale's variance from the fit without that scale.
  const Matrix sigma_ci = leave_one_scale_out_covariance(layout, c, lm.p, model, fin.sigma);
  const Matrix cov = log_covariance(fin.whiten * d, fin.whiten * sigma_ci * fin.whiten.transpose(), fixed);
  std::vector<Vector> boot;
  if (options.bootstrap > 0) {
    boot = bootstrap_parameters(layout, lm.p, c, fin.whiten, options.bootstrap, options.seed, options.threads);
    result.bootstrap_replicates = static_cast<int>(boot.size());
  }
  const double zq = detail_normal_quantile(options.level);
  // Reported intervals: the hull of the delta-method (Wald) interval and the profile interval
  // (gmwm_profile.cpp). Wald alone is too narrow where the objective is curved in the parameter
  // (T_c of a term near the record's end), the profile alone where the weight is estimated at
  // the fit (K); docs/fit.md has the coverage of each. The profile's rise is scaled so that a
  // locally linear model gives the Wald interval exactly: rise = zq^2 Var_sandwich / Var_W, with
  // Var_W = (D' W D)^-1 the curvature the objective has in that parameter. Identification keeps
  // to the Wald ends: a profile that reaches a bound says another labelling of the same curve
  // fits as well, which widens the interval but does not make the term noise.
  std::vector<std::pair<double, double>> wald(static_cast<std::size_t>(layout.parameters));
  std::vector<std::pair<double, double>> ends(wald.size());
  {
    const auto kk = static_cast<Eigen::Index>(k);
    const Matrix var_w = log_covariance(fin.whiten * d, Matrix::Identity(kk, kk), fixed);
    std::vector<double> rise(wald.size(), std::numeric_limits<double>::quiet_NaN());
    const ProfileObjective linear{fin.whiten, {}, {}};
    for (Eigen::Index j = 0; j < layout.parameters; ++j) {
      const auto u = static_cast<std::size_t>(j);
      const double sd = std::sqrt(cov(j, j));
      wald[u] = ends[u] = {lm.p(j) - zq * sd, lm.p(j) + zq * sd};
      if (!std::isfinite(sd) || !(var_w(j, j) > 0.0) || !std::isfinite(var_w(j, j))) continue;
      rise[u] = zq * zq * cov(j, j) / var_w(j, j);
      const auto [lo, hi] = profile_interval(layout, c, linear, bounds, lm.p, lm.cost, j, rise[u],
                                               std::clamp(sd, 0.02, 1.0));
      ends[u] = {std::min(ends[u].first, lo), std::max(ends[u].second, hi)};
    }
    // The profile of the cube-root-score objective, a piece of each set too: the linear form's
    // rise is a Gaussian's, and at the long scales (a random walk's, a slow term's) an estimate is
    // a chi-square of a few degrees of freedom; in the scores it is nearly Gaussian, as J's
    // residuals are. Its minimum is near the optimum, not at it: the profile starts there, and its
    // rise is zq^2 (the weight is the efficient one). Three-AR1 records of docs/fit.md: K at its
    // floor with the 50 s term carrying the random walk, the truth outside the linear profile.
    // With the diagonal weight zq^2 would not be calibrated: the linear profile only.
    if (c.full_weight) {
      const ProfileObjective scored = score_objective(fin.whiten, fin.sigma, model);
      const LmResult at = minimise(scored, layout, c, bounds, lm.p);
      for (Eigen::Index j = 0; j < layout.parameters && std::isfinite(at.cost); ++j) {
        const auto u = static_cast<std::size_t>(j);
        if (!std::isfinite(rise[u])) continue;
        const auto [lo, hi] = profile_interval(layout, c, scored, bounds, at.p, at.cost, j, zq * zq,
                                               std::clamp(std::sqrt(cov(j, j)), 0.02, 1.0));
        ends[u] = {std::min(ends[u].first, lo), std::max(ends[u].second, hi)};
      }
    }
    // The profile set's other pieces: another labelling of the Gauss-Markov terms whose objective
    // is within a parameter's rise of the optimum is inside that parameter's profile set, and so
    // is the piece a profile marched from it finds (three-AR1 records of docs/fit.md: a spurious
    // fast term with K carrying the 50 s term, the true labelling 0.3-2 above the optimum).
    constexpr std::size_t kOtherPieces = 2;
    double widest = 0.0;
    for (const double r : rise) {
      if (std::isfinite(r)) widest = std::max(widest, r);
    }
    for (const LmResult& other : near_optima(layout, c, fin.whiten, lm, widest, kOtherPieces)) {
      const auto other_fixed = at_floor(layout, other.p, bounds);
      for (Eigen::Index j = 0; j < layout.parameters; ++j) {
        const auto u = static_cast<std::size_t>(j);
        if (!std::isfinite(rise[u]) || other.cost - lm.cost > rise[u]) continue;
        // A term at its floor there: its variance may be nil, its shape is arbitrary.
        if (other_fixed[u]) {
          if (std::find(layout.magnitude.begin(), layout.magnitude.end(), j) != layout.magnitude.end()) {
            ends[u].first = std::min(ends[u].first, other.p(j));
          }
          continue;
        }
        const auto [lo, hi] = profile_interval(layout, c, linear, bounds, other.p, lm.cost, j, rise[u],
                                               std::clamp(std::sqrt(cov(j, j)), 0.02, 1.0));
        ends[u] = {std::min({ends[u].first, lo, other.p(j)}), std::max({ends[u].second, hi, other.p(j)})};
      }
    }
  }
  auto percentile = [&](Eigen::Index j, double q) {
    std::vector<double> v;
    for (const auto& b : boot) v.push_back(b(j));
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
  };
  const double span_lo = tau0_s, span_hi = static_cast<double>(n_phase - 1) * tau0_s;
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    GmwmTermEstimate e;
    e.kind = layout.terms[t];
    const Eigen::Index j = layout.magnitude[t];
    const double sd = std::sqrt(cov(j, j));
    const double mag = std::exp(0.5 * lm.p(j));
    const bool floor = fixed[static_cast<std::size_t>(j)];
    e.magnitude.value = mag;
    e.magnitude_fitted = mag;
    const auto [mag_lo, mag_hi] = ends[static_cast<std::size_t>(j)];
    e.magnitude.ci_low = std::isfinite(sd) && mag_lo > bounds.lo(j) ? std::exp(0.5 * mag_lo) : 0.0;
    e.magnitude.ci_high = std::isfinite(sd) ? std::exp(0.5 * mag_hi) : std::exp(0.5 * bounds.hi(j));
    e.magnitude.identified = !floor && sd < 1.0 / zq;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    e.shape.ci_low = e.shape.ci_high = nan;
    e.magnitude_boot_low = boot.empty() ? nan : std::exp(0.5 * percentile(j, 0.5 - 0.5 * options.level));
    e.magnitude_boot_high = boot.empty() ? nan : std::exp(0.5 * percentile(j, 0.5 + 0.5 * options.level));
    e.shape_boot_low = e.shape_boot_high = nan;
    if (layout.shape[t] >= 0) {
      const Eigen::Index s = layout.shape[t];
      const double ssd = std::sqrt(cov(s, s));
      e.shape.value = std::exp(lm.p(s));
      e.shape_fitted = e.shape.value;
      const auto [shape_lo, shape_hi] = ends[static_cast<std::size_t>(s)];
      e.shape.ci_low = std::isfinite(ssd) ? std::exp(shape_lo) : 0.0;
      e.shape.ci_high = std::isfinite(ssd) ? std::exp(shape_hi) : std::numeric_limits<double>::infinity();
      e.shape.identified = e.magnitude.identified && std::isfinite(ssd);
      if (!boot.empty()) {
        e.shape_boot_low = std::exp(percentile(s, 0.5 - 0.5 * options.level));
        e.shape_boot_high = std::exp(percentile(s, 0.5 + 0.5 * options.level));
      }
      const auto [wald_lo, wald_hi] = wald[static_cast<std::size_t>(s)];
      if (e.kind == GmwmTerm::GM && e.shape.identified &&
          (std::exp(wald_lo) < span_lo || std::exp(wald_hi) > span_hi)) {
        e.shape.identified = false;
        e.magnitude.identified = false;
        e.shape.note = e.magnitude.note = fmt::format(
            "correlation time {:.4g} s, its interval [{:.4g}, {:.4g}] s reaches outside the record's "
            "span [{:g}, {:g}] s: a Gauss-Markov term that white noise or a random walk describes",
            e.shape.value, std::exp(wald_lo), std::exp(wald_hi), span_lo, span_hi);
      }
    }
    if (!e.magnitude.identified && e.magnitude.note.empty()) {
      e.magnitude.note = floor ? fmt::format("not needed by the curve: its variance ran to the floor (estimate {:.4g})", mag)
                               : fmt::format("not significant: the {:g} % interval of its variance on the linear "
                                             "scale includes zero (estimate {:.4g}, log-sd {:.3g})",
                                             100.0 * options.level, mag, sd);
      if (layout.shape[t] >= 0) {
        e.shape.identified = false;
        if (e.shape.note.empty()) e.shape.note = e.magnitude.note;
      }
    }
    if (!e.magnitude.identified) {
      // The convention of every fit: a term not identified has value 0 and an upper limit.
      e.magnitude.ci_low = 0.0;
      e.magnitude.value = 0.0;
      if (!std::isfinite(e.magnitude.ci_high)) e.magnitude.ci_high = std::exp(0.5 * bounds.hi(j));
    }
    result.terms.push_back(e);
  }
  // GM terms ordered by correlation time (the other terms keep their places).
  std::vector<std::size_t> gm_pos;
  for (std::size_t t = 0; t < result.terms.size(); ++t) {
    if (result.terms[t].kind == GmwmTerm::GM) gm_pos.push_back(t);
  }
  std::vector<GmwmTermEstimate> gms;
  for (std::size_t p : gm_pos) gms.push_back(result.terms[p]);
  std::sort(gms.begin(), gms.end(), [](const GmwmTermEstimate& a, const GmwmTermEstimate& b) {
    return a.shape.value < b.shape.value;
  });
  for (std::size_t i = 0; i < gm_pos.size(); ++i) result.terms[gm_pos[i]] = gms[i];
  if (result.status == GmwmStatus::no_convergence) {
    // The last iterate is not an estimate: no term is reported as identified from it.
    const std::string stopped = fmt::format(
        "not identified: the gmwm fit of {} did not converge in {} iterations (the last iterate is no "
        "estimate); fix: fewer terms (--terms auto selects among smaller models), a longer record or "
        "--method wls",
        result.model, lm.iterations);
    for (auto& e : result.terms) {
      for (Coefficient* coef : {&e.magnitude, &e.shape}) {
        coef->identified = false;
        coef->note = stopped;
      }
      e.magnitude.value = 0.0;
      e.magnitude_fitted = 0.0;
      e.magnitude.ci_low = 0.0;
      e.magnitude.ci_high = std::numeric_limits<double>::quiet_NaN();
    }
    result.warnings.push_back("gmwm: " + result.model + " " + stopped);
  }
  // BGM: the Gauss-Markov states it stands for, with B's interval and verdict.
  for (auto& e : result.terms) {
    if (e.kind != GmwmTerm::BGM) continue;
    const FlickerMixture& mix = c.flicker_mixture;
    for (std::size_t q = 0; q < mix.correlation_time_s.size(); ++q) {
      const double r = std::sqrt(mix.variance_per_b2[q]);
      GaussMarkovTerm s;
      s.sigma.value = r * e.magnitude.value;
      s.sigma.ci_low = r * e.magnitude.ci_low;
      s.sigma.ci_high = r * e.magnitude.ci_high;
      s.sigma.identified = e.magnitude.identified;
      s.sigma.note = fmt::format("state {} of {} of the flicker mixture BGM: sigma = B sqrt({:.4g})", q + 1,
                                 mix.correlation_time_s.size(), mix.variance_per_b2[q]);
      if (!e.magnitude.identified) s.sigma.note += "; B not identified: " + e.magnitude.note;
      s.correlation_time_s.value = mix.correlation_time_s[q];
      s.correlation_time_s.ci_low = s.correlation_time_s.ci_high = mix.correlation_time_s[q];
      s.correlation_time_s.identified = e.magnitude.identified;
      s.correlation_time_s.note = "fixed by the flicker mixture BGM (not estimated)";
      e.states.push_back(std::move(s));
    }
  }
  if (result.j_p_value < 1e-3) {
    result.warnings.push_back(fmt::format(
        "gmwm: the J test rejects the model {} (J = {:.1f} on {} dof, p = {:.2g}): the curve is not "
        "described to within its sampling noise",
        result.model, result.j_statistic, result.dof, result.j_p_value));
  }
  return result;
}

}  // namespace imunoise::fit
