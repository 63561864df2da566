// GMWM: profile intervals of one parameter (gmwm_detail.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "cube_root_score.hpp"
#include "gmwm_detail.hpp"

namespace imunoise::fit::detail {
namespace {

/// The score objective's residual sd_i z_i(a_i) at the model values a (cube_root_score_residual
/// with each scale's dof and sd held) and, in *slope, -d r_i / d a_i (positive).
Vector score_residual(const ProfileObjective& o, const GmwmCurve& c, const Vector& a, Vector* slope) {
  Vector r(a.size());
  if (slope != nullptr) slope->resize(a.size());
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const ScoreResidual s =
        cube_root_score_residual(c.avar[static_cast<std::size_t>(i)], a(i), o.scale_dof(i), o.scale_sd(i));
    r(i) = s.r;
    if (slope != nullptr) (*slope)(i) = -s.dr_da;
  }
  return r;
}

/// The score objective ||Wh r(p)||^2 at p.
double score_cost(const ProfileObjective& o, const Layout& layout, const GmwmCurve& c, const Vector& p) {
  return (o.whiten * score_residual(o, c, model_avar(layout, p, c, nullptr), nullptr)).squaredNorm();
}

}  // namespace

ProfileObjective score_objective(const Matrix& wh, const Matrix& sigma, const Vector& model) {
  ProfileObjective o{wh, Vector(model.size()), Vector(model.size())};
  for (Eigen::Index i = 0; i < model.size(); ++i) {
    o.scale_sd(i) = std::sqrt(sigma(i, i));
    o.scale_dof(i) = 2.0 * model(i) * model(i) / sigma(i, i);
  }
  return o;
}

LmResult minimise(const ProfileObjective& o, const Layout& layout, const GmwmCurve& c, const Bounds& bounds,
                  const Vector& from) {
  if (o.scale_dof.size() == 0) return levenberg_marquardt(layout, c, o.whiten, from, bounds, c.max_iterations);
  // r(a) ~ r(a0) - s (a - a0) = s (y* - a) with y* = a0 + r(a0) / s: a linear fit of the
  // pseudo-data y* with the whitener Wh diag(s), repeated at the new a0.
  constexpr int kSteps = 8;
  // `from` itself when no step lowers the objective (it is then the local minimum found).
  LmResult cur;
  cur.p = from;
  cur.cost = score_cost(o, layout, c, from);
  cur.converged = true;
  GmwmCurve pseudo = c;
  for (int step = 0; step < kSteps; ++step) {
    const Vector a0 = model_avar(layout, cur.p, c, nullptr);
    Vector s;
    const Vector r0 = score_residual(o, c, a0, &s);
    for (Eigen::Index i = 0; i < a0.size(); ++i) pseudo.avar[static_cast<std::size_t>(i)] = a0(i) + r0(i) / s(i);
    const LmResult next = levenberg_marquardt(layout, pseudo, o.whiten * s.asDiagonal(), cur.p, bounds, c.max_iterations);
    const double cost = next.p.allFinite() ? score_cost(o, layout, c, next.p) : std::numeric_limits<double>::infinity();
    if (!std::isfinite(cost) || cost > cur.cost + 1e-9 * std::max(1.0, cur.cost)) break;
    const double move = (next.p - cur.p).cwiseAbs().maxCoeff();
    cur.p = next.p;
    cur.cost = cost;
    cur.converged = next.converged;
    cur.iterations += next.iterations;
    if (move < 1e-5) break;
  }
  return cur;
}

namespace {

/// Whether the refitted point q is still the model fitted at p: no other term's magnitude has
/// run to its floor that was above it at p, and the Gauss-Markov terms keep their order of
/// correlation time. Past such a point the profile describes another model (one term taking
/// over another's role), so its ends would say nothing about this model's parameter.
bool same_model(const Layout& layout, const Bounds& bounds, const Vector& p, const Vector& q, Eigen::Index j) {
  constexpr double kAtFloor = 1e-3;  // log-variance units: LM clamps to the bound exactly
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const Eigen::Index i = layout.magnitude[t];
    if (i == j) continue;
    if (p(i) > bounds.lo(i) + kAtFloor && q(i) <= bounds.lo(i) + kAtFloor) return false;
  }
  for (std::size_t a = 0; a < layout.terms.size(); ++a) {
    for (std::size_t b = 0; b < layout.terms.size(); ++b) {
      if (layout.terms[a] != GmwmTerm::GM || layout.terms[b] != GmwmTerm::GM) continue;
      const Eigen::Index sa = layout.shape[a], sb = layout.shape[b];
      if (p(sa) < p(sb) && !(q(sa) < q(sb))) return false;
    }
  }
  return true;
}

/// Whether a magnitude other than parameter j is at its floor in q (at_floor).
bool other_term_at_floor(const Layout& layout, const Bounds& bounds, const Vector& q, Eigen::Index j) {
  const auto floors = at_floor(layout, q, bounds);
  return std::any_of(layout.magnitude.begin(), layout.magnitude.end(),
                     [&](Eigen::Index i) { return i != j && floors[static_cast<std::size_t>(i)]; });
}

/// The objective with parameter j held at `value` and every other parameter refitted from
/// `warm` (which it updates: the next point starts where this one ended); +inf where the
/// refit leaves the model fitted at p (same_model).
double profiled_cost(const Layout& layout, const GmwmCurve& c, const ProfileObjective& o, const Bounds& bounds,
                     const Vector& p, Eigen::Index j, double value, Vector& warm) {
  Bounds held = bounds;
  held.lo(j) = held.hi(j) = value;
  Vector start = warm;
  start(j) = value;
  LmResult best;
  best.cost = std::numeric_limits<double>::infinity();
  auto refit = [&](const Vector& from) {
    LmResult r = minimise(o, layout, c, held, from);
    if (std::isfinite(r.cost) && r.cost < best.cost && same_model(layout, bounds, p, r.p, j)) best = std::move(r);
  };
  refit(start);
  // A term at its floor has no gradient in its log-variance, so a refit from the warm point
  // can never bring it back; yet with j held away from the optimum that term may be what the
  // curve needs (K taking over the random walk a slow Gauss-Markov term carried at p). A second
  // start with every variance re-solved by NNLS at the held shapes lets it.
  if (other_term_at_floor(layout, bounds, std::isfinite(best.cost) ? best.p : start, j)) {
    Vector revived = start;
    magnitudes_by_nnls(layout, c, o.whiten, bounds, revived);
    revived(j) = value;
    refit(revived);
  }
  if (!std::isfinite(best.cost)) return std::numeric_limits<double>::infinity();
  warm = best.p;
  return best.cost;
}

/// The end of the interval on one side (direction +1 or -1): march out with doubling steps
/// until the profiled objective rises by more than `rise`, then bisect the bracket.
double profile_end(const Layout& layout, const GmwmCurve& c, const ProfileObjective& o, const Bounds& bounds,
                   const Vector& p, double cost, Eigen::Index j, double rise, double step, int direction) {
  constexpr int kExpansions = 12;
  constexpr int kBisections = 10;
  const double edge = direction > 0 ? bounds.hi(j) : bounds.lo(j);
  double inside = p(j);
  Vector warm_inside = p;
  // Whether v is inside the interval; if so it becomes the innermost known end.
  auto accept = [&](double v) {
    Vector warm = warm_inside;
    const double q = profiled_cost(layout, c, o, bounds, p, j, v, warm);
    if (!std::isfinite(q) || q - cost > rise) return false;
    inside = v;
    warm_inside = std::move(warm);
    return true;
  };
  double outside = edge;
  bool bracketed = false;
  for (int e = 0; e < kExpansions && !bracketed; ++e) {
    const double v = direction > 0 ? std::min(inside + step, edge) : std::max(inside - step, edge);
    if (!accept(v)) {
      outside = v;
      bracketed = true;
    } else if (v == edge) {
      return edge;
    }
    step *= 2.0;
  }
  if (!bracketed) return inside;
  for (int b = 0; b < kBisections; ++b) {
    const double v = 0.5 * (inside + outside);
    if (!accept(v)) outside = v;
  }
  return inside;
}

}  // namespace

std::pair<double, double> profile_interval(const Layout& layout, const GmwmCurve& c, const ProfileObjective& o,
                                           const Bounds& bounds, const Vector& p, double cost, Eigen::Index j,
                                           double rise, double step) {
  return {profile_end(layout, c, o, bounds, p, cost, j, rise, step, -1),
          profile_end(layout, c, o, bounds, p, cost, j, rise, step, +1)};
}

}  // namespace imunoise::fit::detail
