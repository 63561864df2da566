#pragma once
// Deviations of a record split into independent segments (at timestamp gaps, rejected spikes,
// or the runs of a temperature bin), pooled without ever joining or interpolating.
//
// Every estimator of the Allan family is a mean of squared finite differences,
//   var(tau) = S(tau) / (c(tau) n(tau)),
// with S the sum of n squared terms and c a constant of m and tau only (allan.hpp,
// modified_allan.hpp, hadamard.hpp). The pooled estimate is that same mean over every term that
// lies inside one segment:
//   var_pooled = sum_s S_s / (c sum_s n_s) = sum_s n_s var_s / sum_s n_s,
// i.e. the one-record estimator with the terms that would span a break left out. This holds for
// adev, oadev, mdev, tdev (tau^2/3 mdev^2: the same weights), hdev and ohdev.
//
// EDF: the noise type at each factor is identified on the longest segment (the same
// identification as an unsplit record, fill_confidence.hpp) or forced; each segment's EDF is
// Greenhall & Riley's for its own length (the IEEE 952 n/m - 1 when no type is known); the
// pooled estimate is the n_s-weighted mean of independent chi-squared estimates, whose EDF is
// Satterthwaite's  edf = (sum n_s)^2 / sum (n_s^2 / edf_s)  (equal to sum edf_s when the edf
// are proportional to the term counts, smaller otherwise). The chi-squared bounds use it.
//
// Not poolable (pooling_refusal says why): the total family (totdev, mtotdev, ttotdev,
// htotdev) extends the record by reflection at its two ends, so a segment's extension at a gap
// is not the record's; theo1 and theobr (ThêoBR's bias factor is a ratio over one record, and
// Theo1's EDF tables are for one record); mtie and tierms are not variances of differences.
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/preprocess/preprocess.hpp"

namespace imunoise::preprocess {

/// Empty when `estimator` can be pooled over segments; otherwise one sentence saying why not.
std::string_view pooling_refusal(Estimator estimator);

struct PoolOptions {
  double level = 0.683;             ///< two-sided confidence level of the bounds
  std::optional<int> forced_alpha;  ///< noise type at every tau instead of identifying it
  bool no_ci = false;               ///< skip identification, EDF and bounds
  unsigned threads = 0;             ///< 0: all cores; results do not depend on it
};

struct PooledCurve {
  std::vector<DevPoint> points;              ///< SI; n = terms pooled; edf, bounds, alpha set
  std::vector<PointConfidence> confidence;   ///< per point (empty with no_ci): the longest
                                             ///< segment's noise identification, the pooled EDF
  std::size_t segments_used = 0;             ///< segments with at least one term at some factor
};

/// `estimator` of rate samples (SI, spaced tau0_s) split into `segments`, each integrated on its
/// own (angle from 0, its own mean rate removed: constants cancel in every difference). A factor
/// is kept when at least one segment has a term at it. Throws InputError when the estimator
/// cannot be pooled (pooling_refusal) or a segment lies outside the samples.
PooledCurve pooled_deviation(Estimator estimator, std::span<const double> rate_si,
                             std::span<const Segment> segments, double tau0_s,
                             std::span<const std::size_t> factors, const PoolOptions& options = {});

}  // namespace imunoise::preprocess
