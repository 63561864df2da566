#include "imunoise/preprocess/pooled_deviation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"

namespace imunoise::preprocess {

std::string_view pooling_refusal(Estimator estimator) {
  switch (estimator) {
    case Estimator::adev:
    case Estimator::oadev:
    case Estimator::mdev:
    case Estimator::tdev:
    case Estimator::hdev:
    case Estimator::ohdev:
      return {};
    case Estimator::totdev:
    case Estimator::mtotdev:
    case Estimator::ttotdev:
    case Estimator::htotdev:
      return "the total family extends the record by reflection at its two ends, so each segment "
             "would be reflected at a gap: a different estimator, not a pooled sum";
    case Estimator::theo1:
    case Estimator::theobr:
      return "ThêoBR's bias factor is an Avar/Theo1 ratio over one record and Theo1's EDF is "
             "tabulated for one record; pooling them is not implemented";
    case Estimator::mtie:
    case Estimator::tierms:
      return "time-interval errors are not variances of differences, so there are no sums to pool";
  }
  return "unknown estimator";
}

namespace {

constexpr int kNoAlpha = std::numeric_limits<int>::min();

// One segment's EDF at factor m over n_phase angle samples: Greenhall & Riley for the
// identified noise type, else the noise-blind IEEE 952 value.
double segment_edf(Estimator estimator, int alpha, std::size_t m, std::size_t n_phase) {
  if (alpha != kNoAlpha && alpha_in_domain(estimator, alpha)) {
    if (const auto variance = difference_variance(estimator)) {
      const double e = greenhall_riley_edf(alpha, *variance, m, n_phase);
      if (std::isfinite(e) && e > 0.0) return e;
    }
  }
  const double e = ieee952_edf(m, n_phase);
  return std::isfinite(e) && e > 0.0 ? e : 1.0;
}

}  // namespace

PooledCurve pooled_deviation(Estimator estimator, std::span<const double> rate_si,
                             std::span<const Segment> segments, double tau0_s,
                             std::span<const std::size_t> factors, const PoolOptions& options) {
  if (const auto why = pooling_refusal(estimator); !why.empty()) {
    throw InputError(std::string(estimator_name(estimator)) + " cannot be pooled over the segments of a split "
                     "record: " + std::string(why) + "; fix: use adev, oadev, mdev, tdev, hdev or ohdev, or "
                     "analyse one segment");
  }
  for (const Segment& s : segments) {
    if (s.begin > s.end || s.end > rate_si.size()) {
      throw InputError("segment [" + std::to_string(s.begin) + ", " + std::to_string(s.end) + ") lies outside the " +
                       std::to_string(rate_si.size()) + " rate samples");
    }
  }
  const std::size_t k = factors.size();
  // Per factor: sum of n_s var_s (= S_s / c), sum of n_s, and per segment (n_s, n_phase_s) for the EDF.
  std::vector<long double> weighted(k, 0.0L);
  std::vector<std::size_t> count(k, 0);
  struct Share {
    std::size_t n = 0;
    std::size_t n_phase = 0;
  };
  std::vector<std::vector<Share>> shares(k);
  std::vector<double> tau(k, 0.0);
  PooledCurve out;
  // The longest segment identifies the noise type (its phase is kept for fill_confidence).
  std::size_t longest = segments.size();
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (longest == segments.size() || segments[s].size() > segments[longest].size()) longest = s;
  }
  std::vector<double> longest_phase;
  std::vector<DevPoint> longest_points;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Segment& seg = segments[s];
    if (seg.size() < 2) continue;
    const auto rate = rate_si.subspan(seg.begin, seg.size());
    std::vector<double> phase = phase_from_rate(rate, tau0_s, compensated_mean(rate));
    const std::size_t max_m = max_averaging_factor(estimator, phase.size());
    std::vector<std::size_t> local;
    std::vector<std::size_t> where;
    for (std::size_t j = 0; j < k; ++j) {
      if (factors[j] >= 1 && factors[j] <= max_m) {
        local.push_back(factors[j]);
        where.push_back(j);
      }
    }
    if (local.empty()) continue;
    ++out.segments_used;
    auto points = compute_deviation(estimator, phase, tau0_s, local, {options.threads});
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::size_t j = where[i];
      const long double dev = points[i].dev;
      weighted[j] += static_cast<long double>(points[i].n) * dev * dev;
      count[j] += points[i].n;
      tau[j] = points[i].tau_s;
      shares[j].push_back({points[i].n, phase.size()});
    }
    if (s == longest) {
      longest_phase = std::move(phase);
      longest_points = std::move(points);
    }
  }
  // Noise identification on the longest segment, at its factors (every kept factor is one of them:
  // the longest segment has the most terms at every m).
  std::vector<PointConfidence> longest_confidence;
  if (!options.no_ci && !longest_points.empty()) {
    ConfidenceOptions c;
    c.level = options.level;
    c.forced_alpha = options.forced_alpha;
    c.threads = options.threads;
    longest_confidence = fill_confidence(longest_points, estimator, longest_phase, c);
  }
  for (std::size_t j = 0; j < k; ++j) {
    if (count[j] == 0) continue;
    DevPoint p;
    p.m = factors[j];
    p.tau_s = tau[j];
    p.n = count[j];
    p.dev = static_cast<double>(std::sqrt(weighted[j] / static_cast<long double>(count[j])));
    if (!options.no_ci) {
      PointConfidence confidence;
      int alpha = kNoAlpha;
      EdfMethod method = EdfMethod::ieee952_simple;
      for (std::size_t i = 0; i < longest_points.size(); ++i) {
        if (longest_points[i].m != p.m) continue;
        alpha = longest_points[i].alpha;
        if (i < longest_confidence.size()) {
          confidence.noise = longest_confidence[i].noise;
          if (longest_confidence[i].edf.method == EdfMethod::greenhall_riley) method = EdfMethod::greenhall_riley;
        }
      }
      // Satterthwaite: the n_s-weighted mean of independent sigma^2 chi2(edf_s)/edf_s.
      long double inverse = 0.0L;
      for (const Share& share : shares[j]) {
        const long double w = static_cast<long double>(share.n) / static_cast<long double>(p.n);
        inverse += w * w / segment_edf(estimator, alpha, p.m, share.n_phase);
      }
      p.edf = static_cast<double>(1.0L / inverse);
      p.alpha = alpha;
      const auto ci = chi2_interval(p.dev, p.edf, options.level);
      p.ci_low = ci.low;
      p.ci_high = ci.high;
      confidence.edf = {p.edf, method};
      out.confidence.push_back(std::move(confidence));
    }
    out.points.push_back(p);
  }
  return out;
}

}  // namespace imunoise::preprocess
