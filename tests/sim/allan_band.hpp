#pragma once
// Confidence bands for simulated overlapping Allan variances, for the validation tests.
//
// EDF: the closed-form approximations for the overlapping Allan variance of NIST SP 1065
// (W. Riley, Handbook of Frequency Stability Analysis, 2008, section 5.2.3, Table 5; from
// Howe, Allan and Barnes 1981), with N the number of phase (angle) points and m the averaging
// factor, per power-law noise type alpha of the rate (S_y ~ f^alpha):
//   alpha = +2 (white PM = angle white noise Q):   (N+1)(N-2m) / (2(N-m))
//   alpha = +1 (flicker PM):                       exp(sqrt(ln((N-1)/(2m)) ln((2m+1)(N-1)/4)))
//   alpha =  0 (white FM = angle random walk N):   (3(N-1)/(2m) - 2(N-2)/N) 4m^2/(4m^2+5)
//   alpha = -1 (flicker FM = bias instability B):  m = 1: 2(N-2)^2/(2.3N-4.9); else 5N^2/(4m(N+3m))
//   alpha = -2 (random-walk FM = rate random walk K): (N-2)/m ((N-1)^2 - 3m(N-1) + 4m^2)/(N-3)^2
// (the m = 1 flicker FM form is SP 1065's; some codes drop the square, which gives edf < 1.)
// Band: edf * avar_hat / avar ~ chi^2(edf), so avar_hat lies in
// [avar chi2_q(p/2)/edf, avar chi2_q(1-p/2)/edf] with probability 1 - p.
//
// Level. Each test compares every point of its tau grid; the whole suite compares fewer than
// 200 points. With p = 1e-5 per point, Bonferroni bounds the probability that any point of
// the suite falls outside its band by 200 * 1e-5 = 0.2 %, even allowing for the ~10-20 %
// uncertainty of these EDF approximations (which moves the per-point level to at most ~1e-4
// and the family to ~2 %). The bands are not tuned: they follow from the formulas above.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>

namespace imunoise::sim::test {

inline constexpr double kPerPointFalseAlarm = 1e-5;

inline double sp1065_oadev_edf(int alpha, double n_phase, double m) {
  const double N = n_phase;
  switch (alpha) {
    case 2: return (N + 1.0) * (N - 2.0 * m) / (2.0 * (N - m));
    case 1: return std::exp(std::sqrt(std::log((N - 1.0) / (2.0 * m)) * std::log((2.0 * m + 1.0) * (N - 1.0) / 4.0)));
    case 0: return (3.0 * (N - 1.0) / (2.0 * m) - 2.0 * (N - 2.0) / N) * 4.0 * m * m / (4.0 * m * m + 5.0);
    case -1:
      if (m == 1.0) return 2.0 * (N - 2.0) * (N - 2.0) / (2.3 * N - 4.9);
      return 5.0 * N * N / (4.0 * m * (N + 3.0 * m));
    default:
      return (N - 2.0) / m * ((N - 1.0) * (N - 1.0) - 3.0 * m * (N - 1.0) + 4.0 * m * m) /
             ((N - 3.0) * (N - 3.0));
  }
}

struct Band {
  double low = 0.0;   ///< variance bounds
  double high = 0.0;
  double edf = 0.0;
};

/// Band for the estimated Allan variance around the true avar, given the EDF.
inline Band chi2_band(double avar, double edf, double p = kPerPointFalseAlarm) {
  boost::math::chi_squared dist(edf);
  Band b;
  b.edf = edf;
  b.low = avar * boost::math::quantile(dist, p / 2.0) / edf;
  b.high = avar * boost::math::quantile(dist, 1.0 - p / 2.0) / edf;
  return b;
}

/// Mixture: the smallest EDF among the noise types whose share of the variance is >= 10 %
/// (the widest of their bands: conservative, never tuned).
inline double mixture_edf(const std::vector<std::pair<int, double>>& alpha_and_share, double n_phase,
                          double m) {
  double edf = 0.0;
  bool any = false;
  for (const auto& [alpha, share] : alpha_and_share) {
    if (share < 0.1) continue;
    const double e = sp1065_oadev_edf(alpha, n_phase, m);
    edf = any ? std::min(edf, e) : e;
    any = true;
  }
  return edf;
}

}  // namespace imunoise::sim::test
