// GMWM estimator, WVIC model selection and intervals (see include/imunoise/fit/gmwm.hpp and
// docs/fit.md, section "GMWM").
#include "imunoise/fit/gmwm.hpp"

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
#include "gmwm_detail.hpp"
#include "least_squares.hpp"

namespace imunoise::fit {

using detail::Matrix;
using detail::Vector;

const char* gmwm_term_name(GmwmTerm term) {
  switch (term) {
    case GmwmTerm::Q: return "Q";
    case GmwmTerm::N: return "N";
    case GmwmTerm::B: return "B";
    case GmwmTerm::K: return "K";
    case GmwmTerm::R: return "R";
    case GmwmTerm::GM: return "GM";
    case GmwmTerm::SIN: return "SIN";
    case GmwmTerm::BGM: return "BGM";
  }
  return "?";
}

std::string gmwm_status_name(GmwmStatus status) {
  switch (status) {
    case GmwmStatus::converged: return "converged";
    case GmwmStatus::no_convergence: return "no_convergence";
    case GmwmStatus::too_few_scales: return "too_few_scales";
  }
  return "?";
}

double gmwm_avar_quantization(double tau_s) { return 3.0 / (tau_s * tau_s); }
double gmwm_avar_white(double tau_s) { return 1.0 / tau_s; }
double gmwm_avar_flicker(double) { return 2.0 * std::numbers::ln2 / std::numbers::pi; }
double gmwm_avar_random_walk(double tau_s) { return tau_s / 3.0; }
double gmwm_avar_ramp(double tau_s) { return 0.5 * tau_s * tau_s; }

double gmwm_avar_ar1(double tc_s, double tau0_s, std::size_t m) {
  const double md = static_cast<double>(m);
  const double tau = md * tau0_s;
  const double y = tau0_s / tc_s;
  if (tc_s < tau0_s) {
    // Direct form: phi is small, nothing cancels.
    const double phi = std::exp(-y);
    const double pm = std::pow(phi, md);
    return (md * (1.0 + phi) / (1.0 - phi) - phi * (3.0 - 4.0 * pm + pm * pm) / ((1.0 - phi) * (1.0 - phi))) /
           (md * md);
  }
  // sigma^2 [A (4 s(X) - s(2X)) + 2 (B T - A) X] / tau^2, X = tau / T, with the kernel of
  // covariance.cpp (A, B T - A from tau0 and T; s(x) = e^-x - 1 + x - x^2/2).
  const double u = 0.5 * y;
  const double sh = std::sinh(u);
  const double a = tau0_s * tau0_s / (4.0 * sh * sh);
  const double linear = u < 1e-2 ? tc_s * tc_s * u * u * (2.0 / 3.0 - 4.0 * u * u / 45.0)
                                 : 0.5 * tau0_s * tc_s / std::tanh(u) - a;
  auto s = [](double x) {
    if (x >= 2.0) return std::exp(-x) - 1.0 + x - 0.5 * x * x;
    double term = -x * x * x / 6.0, sum = term;
    for (int n = 4; n < 30; ++n) {
      term *= -x / n;
      sum += term;
    }
    return sum;
  };
  const double x = tau / tc_s;
  return (a * (4.0 * s(x) - s(2.0 * x)) + 2.0 * linear * x) / (tau * tau);
}

double gmwm_avar_sinusoid(double f_hz, double tau_s) {
  const double x = std::numbers::pi * f_hz * tau_s;
  if (x == 0.0) return 0.0;
  const double s = std::sin(x);
  const double v = s * s / x;
  return v * v;
}

bool GmwmOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (!automatic && terms.empty()) return fail("gmwm needs at least one term");
  if (!automatic) {
    int gm = 0;
    for (GmwmTerm t : terms) gm += t == GmwmTerm::GM || t == GmwmTerm::BGM;
    if (gm > static_cast<int>(GmwmCovarianceBasis::kMaxAr1)) {
      return fail(fmt::format("gmwm: at most {} GM terms (BGM counts as one)", GmwmCovarianceBasis::kMaxAr1));
    }
    for (GmwmTerm t : terms) {
      for (GmwmTerm u : terms) {
        if (t == GmwmTerm::B && u == GmwmTerm::BGM) {
          return fail("gmwm: B and BGM are the same flicker noise (BGM is B written as Gauss-Markov "
                      "states); list one of them");
        }
      }
    }
    for (std::size_t i = 0; i < terms.size(); ++i) {
      for (std::size_t j = i + 1; j < terms.size(); ++j) {
        if (terms[i] == terms[j] && terms[i] != GmwmTerm::GM) {
          return fail(fmt::format("gmwm: term {} is listed twice (only GM may repeat)",
                                  gmwm_term_name(terms[i])));
        }
      }
    }
  }
  if (max_gm < 0 || max_gm > 4) return fail("gmwm: max_gm must be 0..4");
  if (!(level > 0.0 && level < 1.0)) return fail("gmwm: level must be in (0, 1)");
  if (weight_iterations < 1 || weight_iterations > 20) return fail("gmwm: weight_iterations must be 1..20");
  if (bootstrap < 0 || bootstrap > 100000) return fail("gmwm: bootstrap must be 0..100000");
  if (max_iterations < 1 || max_iterations > 100000) return fail("gmwm: max_iterations must be 1..100000");
  if (flicker_states_per_decade < 1 || flicker_states_per_decade > 4) {
    return fail("gmwm: flicker_states_per_decade must be 1..4");
  }
  if (robust && !(robust_efficiency >= 0.55 && robust_efficiency <= 0.99)) {
    return fail("gmwm: robust_efficiency must be in [0.55, 0.99]");
  }
  return true;
}

void parse_gmwm_terms(std::string_view list, GmwmOptions& options) {
  if (list == "auto") {
    options.automatic = true;
    options.terms.clear();
    return;
  }
  options.automatic = false;
  options.terms.clear();
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = list.find(',', start);
    const std::string_view item =
        list.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    std::string name(item);
    for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (name == "Q") options.terms.push_back(GmwmTerm::Q);
    else if (name == "N") options.terms.push_back(GmwmTerm::N);
    else if (name == "B") options.terms.push_back(GmwmTerm::B);
    else if (name == "K") options.terms.push_back(GmwmTerm::K);
    else if (name == "R") options.terms.push_back(GmwmTerm::R);
    else if (name == "GM") options.terms.push_back(GmwmTerm::GM);
    else if (name == "SIN") options.terms.push_back(GmwmTerm::SIN);
    else if (name == "BGM") options.terms.push_back(GmwmTerm::BGM);
    else {
      throw InputError("unknown gmwm term '" + std::string(item) +
                       "' in --terms; use a comma list of Q, N, B, K, R, GM (may repeat), SIN, BGM "
                       "(flicker as Gauss-Markov states), or auto");
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
}

namespace detail {
namespace {

constexpr double kFloorSpan = 46.0;  // log-variance floor: e^-46 ~ 1e-20 of the term's upper bound

bool has_shape(GmwmTerm t) { return t == GmwmTerm::GM || t == GmwmTerm::SIN; }

/// Unit Allan variance of term t (magnitude 1) with shape parameter `shape` at scale i.
double unit_avar(GmwmTerm t, double shape, const GmwmCurve& c, std::size_t i) {
  const double tau = c.tau_s[i];
  switch (t) {
    case GmwmTerm::Q: return gmwm_avar_quantization(tau);
    case GmwmTerm::N: return gmwm_avar_white(tau);
    case GmwmTerm::B: return gmwm_avar_flicker(tau);
    case GmwmTerm::K: return gmwm_avar_random_walk(tau);
    case GmwmTerm::R: return gmwm_avar_ramp(tau);
    case GmwmTerm::GM: return gmwm_avar_ar1(shape, c.tau0_s, c.m[i]);
    case GmwmTerm::SIN: return gmwm_avar_sinusoid(shape, tau);
    case GmwmTerm::BGM: return gmwm_avar_flicker_mixture(c.flicker_mixture, c.tau0_s, c.m[i]);
  }
  return 0.0;
}

}  // namespace

std::string model_name(const std::vector<GmwmTerm>& terms) {
  std::string s;
  for (GmwmTerm t : terms) s += (s.empty() ? "" : "+") + std::string(gmwm_term_name(t));
  return s;
}

Layout::Layout(std::vector<GmwmTerm> kinds) : terms(std::move(kinds)) {
  // GM terms first by nothing: the order is the user's; the GM sort happens on output.
  for (GmwmTerm t : terms) {
    magnitude.push_back(parameters++);
    shape.push_back(has_shape(t) ? parameters++ : -1);
  }
}

Vector model_avar(const Layout& layout, const Vector& p, const GmwmCurve& c, Matrix* jacobian) {
  const auto k = static_cast<Eigen::Index>(c.tau_s.size());
  Vector a = Vector::Zero(k);
  if (jacobian != nullptr) jacobian->setZero(k, layout.parameters);
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const double theta = std::exp(p(layout.magnitude[t]));
    const double shape = layout.shape[t] >= 0 ? std::exp(p(layout.shape[t])) : 0.0;
    for (Eigen::Index i = 0; i < k; ++i) {
      const double g = unit_avar(layout.terms[t], shape, c, static_cast<std::size_t>(i));
      a(i) += theta * g;
      if (jacobian != nullptr) {
        (*jacobian)(i, layout.magnitude[t]) = theta * g;
        if (layout.shape[t] >= 0) {
          const double h = 1e-5;
          const double gp = unit_avar(layout.terms[t], shape * std::exp(h), c, static_cast<std::size_t>(i));
          const double gm = unit_avar(layout.terms[t], shape * std::exp(-h), c, static_cast<std::size_t>(i));
          (*jacobian)(i, layout.shape[t]) = theta * (gp - gm) / (2.0 * h);
        }
      }
    }
  }
  return a;
}

Matrix model_covariance(const Layout& layout, const Vector& p, const GmwmCurve& c) {
  double theta5[kTermCount] = {0, 0, 0, 0, 0};
  std::vector<double> times, variances;
  double sine_avar_scale = 0.0, mixture_b2 = 0.0;
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const double v = std::exp(p(layout.magnitude[t]));
    switch (layout.terms[t]) {
      case GmwmTerm::Q: theta5[kQ] += v; break;
      case GmwmTerm::N: theta5[kN] += v; break;
      case GmwmTerm::B: theta5[kB] += v; break;
      case GmwmTerm::K: theta5[kK] += v; break;
      case GmwmTerm::R: theta5[kR] += v; break;
      case GmwmTerm::GM:
        times.push_back(std::exp(p(layout.shape[t])));
        variances.push_back(v);
        break;
      case GmwmTerm::SIN: sine_avar_scale = 1.0; break;
      case GmwmTerm::BGM: mixture_b2 = v; break;
    }
  }
  const bool mixture = std::find(layout.terms.begin(), layout.terms.end(), GmwmTerm::BGM) != layout.terms.end();
  const GmwmCovarianceBasis basis(c.m, c.n_phase, c.tau0_s, times, theta5[kB] > 0.0, c.threads,
                                  mixture ? &c.flicker_mixture : nullptr);
  Matrix sigma = to_matrix(basis.covariance(theta5, variances, mixture_b2), c.m.size());
  // Robust estimates (GmwmOptions::robust): their covariance is the classical one over the
  // biweight's Gaussian efficiency (robust_wavelet.hpp; a first approximation, docs/fit.md).
  sigma /= c.efficiency;
  if (sine_avar_scale > 0.0) {
    // A sinusoid is deterministic: it adds no Gaussian variance of its own, but it is not in
    // the kernels either. As the wls fit does, scale each row/column by (model with it) /
    // (model without it): conservative (docs/fit.md).
    Layout without = layout;
    Vector q = p;
    for (std::size_t t = 0; t < layout.terms.size(); ++t) {
      if (layout.terms[t] == GmwmTerm::SIN) q(layout.magnitude[t]) = -700.0;
    }
    const Vector with_sin = model_avar(layout, p, c, nullptr);
    const Vector no_sin = model_avar(without, q, c, nullptr);
    const Vector r = (with_sin.array() / no_sin.array().max(1e-300)).sqrt();
    sigma = r.asDiagonal() * sigma * r.asDiagonal();
  }
  return sigma;
}

Matrix whitener_of(const Matrix& sigma, const GmwmCurve& c) { return whitener(sigma, c.full_weight); }

Vector nnls_lh(const Matrix& a, const Vector& b) {
  // Lawson-Hanson active set on column-scaled a.
  const Eigen::Index n = a.cols();
  Vector scale(n);
  Matrix as = a;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double nrm = a.col(j).norm();
    scale(j) = nrm > 0.0 ? 1.0 / nrm : 0.0;
    as.col(j) *= scale(j);
  }
  Vector x = Vector::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    const Vector w = as.transpose() * (b - as * x);
    Eigen::Index best = -1;
    double wmax = 1e-12 * (as.transpose() * b).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!passive[static_cast<std::size_t>(j)] && scale(j) > 0.0 && w(j) > wmax) {
        wmax = w(j);
        best = j;
      }
    }
    if (best < 0) break;
    passive[static_cast<std::size_t>(best)] = true;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      std::vector<int> cols;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[static_cast<std::size_t>(j)]) cols.push_back(static_cast<int>(j));
      }
      const Vector z = subset_ls(as, b, cols, nullptr);
      bool ok = true;
      for (std::size_t c = 0; c < cols.size(); ++c) ok = ok && z(static_cast<Eigen::Index>(c)) > 0.0;
      if (ok) {
        x.setZero();
        for (std::size_t c = 0; c < cols.size(); ++c) x(cols[c]) = z(static_cast<Eigen::Index>(c));
        break;
      }
      double alpha = 1.0;
      for (std::size_t c = 0; c < cols.size(); ++c) {
        const double zc = z(static_cast<Eigen::Index>(c));
        const double xc = x(cols[c]);
        if (zc <= 0.0 && xc - zc > 0.0) alpha = std::min(alpha, xc / (xc - zc));
      }
      for (std::size_t c = 0; c < cols.size(); ++c) {
        const double zc = z(static_cast<Eigen::Index>(c));
        x(cols[c]) += alpha * (zc - x(cols[c]));
        if (x(cols[c]) <= 1e-300) {
          x(cols[c]) = 0.0;
          passive[static_cast<std::size_t>(cols[c])] = false;
        }
      }
    }
  }
  return x.cwiseProduct(scale);
}

namespace {

// A scale's estimate can fall far below its expectation where it has few degrees of freedom
// (chi-square with 1 dof is below 1e-3 of its mean in 2.5 % of records): the largest
// expectation its estimate allows at this one-sided level, not the estimate itself, bounds a
// term's variance. Read from the raw estimate, one low longest scale capped K at a tenth of the
// truth on a 3 h Monte-Carlo record (K at its bound, J 8561 on 14 dof).
constexpr double kBoundLevel = 1e-6;

double expectation_bound(const GmwmCurve& c, std::size_t i) {
  const double m = static_cast<double>(c.m[i]);
  const double edf = std::max(1.0, (static_cast<double>(c.n_phase) - 2.0 * m) / m);  // as initial_whitener's
  const boost::math::chi_squared_distribution<double> chi(edf);
  return c.avar[i] * edf / boost::math::quantile(chi, kBoundLevel);
}

}  // namespace

Bounds bounds_for(const Layout& layout, const GmwmCurve& c) {
  Bounds b;
  b.lo = Vector(layout.parameters);
  b.hi = Vector(layout.parameters);
  const double tau_lo = c.tau_s.front(), tau_hi = c.tau_s.back();
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    // Upper bound of the variance: the lowest line of the term's shape touching the curve's
    // largest allowed expectations (every other term is >= 0), at the shape's most favourable
    // value for GM/SIN.
    // A bump (GM, SIN) is below the curve at its peak scale, wherever that is: its variance is
    // at most the curve's largest value over the peak's height (0.617^2 for GM, ~0.52 for SIN;
    // halved for a peak between two dyadic scales). A power law is below the curve everywhere.
    double ub = std::numeric_limits<double>::infinity();
    const double top = *std::max_element(c.avar.begin(), c.avar.end());
    if (layout.terms[t] == GmwmTerm::GM) ub = top / (0.5 * 0.381142);
    else if (layout.terms[t] == GmwmTerm::SIN) ub = top / (0.5 * 0.52);
    else {
      for (std::size_t i = 0; i < c.tau_s.size(); ++i) {
        ub = std::min(ub, expectation_bound(c, i) / unit_avar(layout.terms[t], 0.0, c, i));
      }
    }
    b.lo(layout.magnitude[t]) = std::log(ub) - kFloorSpan;
    b.hi(layout.magnitude[t]) = std::log(ub) + 2.0;
    if (layout.shape[t] >= 0) {
      if (layout.terms[t] == GmwmTerm::GM) {
        // Its peak (1.89 T_c) within the fitted taus: a faster GM is white noise to the curve,
        // and with the floor at 0.1 tau0 one slid there and traded N away (N+GM fits on other
        // ADIS16405 units ran to the iteration limit along that valley, or reported N not
        // identified; with the floor a factor two lower white noise still lost its N).
        b.lo(layout.shape[t]) = std::log(std::max(0.1 * c.tau0_s, tau_lo / 1.8926));
        b.hi(layout.shape[t]) = std::log(20.0 * tau_hi);
      } else {
        b.lo(layout.shape[t]) = std::log(0.3 / tau_hi);
        b.hi(layout.shape[t]) = std::log(0.5 / c.tau0_s);
      }
    }
  }
  return b;
}

LmResult levenberg_marquardt(const Layout& layout, const GmwmCurve& c, const Matrix& whiten,
                             Vector p, const Bounds& bounds, int max_iterations) {
  constexpr double kGradientCosine = 1e-6;
  const Vector y = Eigen::Map<const Vector>(c.avar.data(), static_cast<Eigen::Index>(c.avar.size()));
  auto clamp = [&](Vector& q) { q = q.cwiseMax(bounds.lo).cwiseMin(bounds.hi); };
  clamp(p);
  Matrix d;
  Vector r = whiten * (y - model_avar(layout, p, c, &d));
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  LmResult out;
  int it = 0;
  bool converged = false;
  for (; it < max_iterations; ++it) {
    const Matrix jw = whiten * d;
    Matrix jtj = jw.transpose() * jw;
    const Vector g = jw.transpose() * r;
    // Parameters at a bound with the gradient pushing out are frozen for this step.
    std::vector<bool> frozen(static_cast<std::size_t>(layout.parameters), false);
    for (Eigen::Index j = 0; j < layout.parameters; ++j) {
      if ((p(j) <= bounds.lo(j) + 1e-12 && g(j) < 0.0) || (p(j) >= bounds.hi(j) - 1e-12 && g(j) > 0.0)) {
        frozen[static_cast<std::size_t>(j)] = true;
      }
    }
    // First-order stationarity (MINPACK's gtol): the residual is orthogonal to every free
    // column of the Jacobian to within kGradientCosine. Without it a flat valley (a GM term
    // sliding towards white noise or a random walk) made tiny improving steps until the
    // iteration limit on real ADIS16405 axes, even for N+GM.
    {
      double worst = 0.0;
      for (Eigen::Index j = 0; j < layout.parameters; ++j) {
        if (frozen[static_cast<std::size_t>(j)] || !(jtj(j, j) > 0.0)) continue;
        worst = std::max(worst, std::abs(g(j)) / std::sqrt(jtj(j, j) * std::max(cost, 1e-300)));
      }
      if (worst < kGradientCosine) {
        converged = true;
        break;
      }
    }
    bool improved = false;
    for (int tries = 0; tries < 30; ++tries) {
      Matrix a = jtj;
      for (Eigen::Index j = 0; j < layout.parameters; ++j) {
        a(j, j) += lambda * std::max(jtj(j, j), 1e-12);
      }
      Vector rhs = g;
      for (Eigen::Index j = 0; j < layout.parameters; ++j) {
        if (frozen[static_cast<std::size_t>(j)]) {
          a.row(j).setZero();
          a.col(j).setZero();
          a(j, j) = 1.0;
          rhs(j) = 0.0;
        }
      }
      Vector step = a.ldlt().solve(rhs);
      if (!step.allFinite()) step = a.completeOrthogonalDecomposition().solve(rhs);
      // Keep steps in log space moderate (a factor e^3 at most per iteration).
      const double big = step.cwiseAbs().maxCoeff();
      if (big > 3.0) step *= 3.0 / big;
      Vector q = p + step;
      clamp(q);
      Matrix dq;
      const Vector rq = whiten * (y - model_avar(layout, q, c, &dq));
      const double cq = rq.squaredNorm();
      if (std::isfinite(cq) && cq < cost) {
        const double rel = (cost - cq) / std::max(cost, 1e-300);
        const double move = (q - p).cwiseAbs().maxCoeff();
        p = q;
        r = rq;
        d = dq;
        cost = cq;
        lambda = std::max(lambda / 5.0, 1e-9);
        improved = true;
        if (rel < 1e-10 || move < 1e-7) converged = true;
        break;
      }
      lambda *= 4.0;
      if (lambda > 1e12) break;
    }
    if (!improved) {
      converged = true;  // no descent direction left: a (constrained) stationary point
      break;
    }
    if (converged) break;
  }
  out.p = p;
  out.cost = cost;
  out.iterations = std::min(it + 1, max_iterations);
  out.converged = converged;
  return out;
}

}  // namespace detail

double gmwm_model_avar(const GmwmResult& result, double tau0_s, std::size_t m) {
  if (result.status != GmwmStatus::converged || m == 0) return 0.0;
  const double tau = static_cast<double>(m) * tau0_s;
  double avar = 0.0;
  for (const auto& e : result.terms) {
    const double unit = [&] {
      switch (e.kind) {
        case GmwmTerm::Q: return gmwm_avar_quantization(tau);
        case GmwmTerm::N: return gmwm_avar_white(tau);
        case GmwmTerm::B: return gmwm_avar_flicker(tau);
        case GmwmTerm::K: return gmwm_avar_random_walk(tau);
        case GmwmTerm::R: return gmwm_avar_ramp(tau);
        case GmwmTerm::GM: return gmwm_avar_ar1(e.shape_fitted, tau0_s, m);
        case GmwmTerm::SIN: return gmwm_avar_sinusoid(e.shape_fitted, tau);
        case GmwmTerm::BGM: return gmwm_avar_flicker_mixture(result.flicker_mixture, tau0_s, m);
      }
      return 0.0;
    }();
    avar += e.magnitude_fitted * e.magnitude_fitted * unit;
  }
  return avar;
}

}  // namespace imunoise::fit
