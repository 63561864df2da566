// GMWM: other local optima as good as the fitted one (gmwm_detail.hpp). Where the curve allows
// two labellings of its Gauss-Markov terms (a fast term nobody needs and K carrying the slowest
// term, or the three terms in their own slots), the profile set of a parameter has one piece
// around each; a profile marched from the optimum sees only its own piece.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "gmwm_detail.hpp"

namespace imunoise::fit::detail {
namespace {

/// q with its Gauss-Markov terms' parameters exchanged so that the i-th fastest term of q sits
/// where the i-th fastest term of p does.
Vector relabelled_like(const Layout& layout, const Vector& p, const Vector& q) {
  std::vector<std::size_t> gm;
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    if (layout.terms[t] == GmwmTerm::GM) gm.push_back(t);
  }
  auto by_tc = [&](const Vector& v) {
    std::vector<std::size_t> order = gm;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return v(layout.shape[a]) < v(layout.shape[b]); });
    return order;
  };
  const auto in_p = by_tc(p), in_q = by_tc(q);
  Vector out = q;
  for (std::size_t r = 0; r < gm.size(); ++r) {
    out(layout.magnitude[in_p[r]]) = q(layout.magnitude[in_q[r]]);
    out(layout.shape[in_p[r]]) = q(layout.shape[in_q[r]]);
  }
  return out;
}

/// Whether a and b are the same optimum: same_point, the shape of a term at its floor in both
/// not compared (it is arbitrary there).
bool same_optimum(const Layout& layout, const Bounds& bounds, const Vector& a, const Vector& b) {
  const auto floor_a = at_floor(layout, a, bounds), floor_b = at_floor(layout, b, bounds);
  Vector a2 = a, b2 = b;
  for (std::size_t t = 0; t < layout.terms.size(); ++t) {
    const Eigen::Index s = layout.shape[t];
    if (s >= 0 && floor_a[static_cast<std::size_t>(s)] && floor_b[static_cast<std::size_t>(s)]) a2(s) = b2(s) = 0.0;
  }
  return same_point(a2, b2);
}

/// The optimum p with one Gauss-Markov term moved to a correlation time of the decade grid
/// that no other term is within half a decade of, the variances re-solved by NNLS; least NNLS
/// cost first. Another labelling of the curve often differs from p by one term: K carrying the
/// slowest term and a spurious fast one at p, the slowest in its own slot in the other.
std::vector<Start> moved_term_starts(const Layout& layout, const GmwmCurve& c, const Matrix& whiten,
                                     const Bounds& bounds, const Vector& p) {
  std::vector<Start> out;
  for (std::size_t g = 0; g < layout.terms.size(); ++g) {
    if (layout.terms[g] != GmwmTerm::GM) continue;
    for (const double tc : tc_decade_grid(c, 0.0)) {
      const bool crowded = std::any_of(layout.shape.begin(), layout.shape.end(), [&](Eigen::Index s) {
        return s >= 0 && s != layout.shape[g] && std::abs(p(s) - std::log(tc)) < 0.5 * std::numbers::ln10;
      });
      if (crowded) continue;
      Vector q = p;
      q(layout.shape[g]) = std::clamp(std::log(tc), bounds.lo(layout.shape[g]), bounds.hi(layout.shape[g]));
      const double cost = magnitudes_by_nnls(layout, c, whiten, bounds, q);
      out.push_back({cost, q});
    }
  }
  std::sort(out.begin(), out.end(), [](const Start& a, const Start& b) { return a.cost < b.cost; });
  return out;
}

}  // namespace

std::vector<LmResult> near_optima(const Layout& layout, const GmwmCurve& c, const Matrix& whiten,
                                  const LmResult& best, double rise, std::size_t count) {
  // Up to eight local fits: the optimum with one term moved (the least NNLS costs first; with
  // three GM terms there are usually eight or more), then the fit's own three best starts
  // (another labelling from scratch) if any of the eight are left.
  constexpr std::size_t kStarts = 8;
  constexpr std::size_t kFreshStarts = 3;
  if (std::count(layout.terms.begin(), layout.terms.end(), GmwmTerm::GM) < 2) return {};
  const Bounds bounds = bounds_for(layout, c);
  std::vector<Start> starts = moved_term_starts(layout, c, whiten, bounds, best.p);
  const std::vector<Start> fresh = ranked_starts(layout, c, whiten, bounds);
  starts.insert(starts.end(), fresh.begin(), fresh.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(fresh.size(), kFreshStarts)));
  std::vector<LmResult> found;
  std::vector<Vector> tried;
  for (const Start& s : starts) {
    if (tried.size() >= kStarts) break;
    if (std::any_of(tried.begin(), tried.end(), [&](const Vector& t) { return same_point(t, s.p); })) continue;
    tried.push_back(s.p);
    LmResult r = levenberg_marquardt(layout, c, whiten, s.p, bounds, c.max_iterations);
    if (!r.converged || !std::isfinite(r.cost) || r.cost - best.cost > rise) continue;
    r.p = relabelled_like(layout, best.p, r.p);
    if (same_optimum(layout, bounds, r.p, best.p)) continue;
    if (std::any_of(found.begin(), found.end(), [&](const LmResult& f) { return same_optimum(layout, bounds, f.p, r.p); })) {
      continue;
    }
    found.push_back(std::move(r));
  }
  std::sort(found.begin(), found.end(), [](const LmResult& a, const LmResult& b) { return a.cost < b.cost; });
  if (found.size() > count) found.resize(count);
  return found;
}

}  // namespace imunoise::fit::detail
