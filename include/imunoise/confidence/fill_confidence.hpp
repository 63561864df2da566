#pragma once
// Confidence intervals for a whole deviation curve: noise identification per tau, EDF, and
// chi-squared bounds, written into the DevPoints (deviation.hpp) that compute_deviation made.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/confidence/noise_id.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/estimator.hpp"

namespace imunoise {

struct ConfidenceOptions {
  double level = kDefaultConfidenceLevel;  ///< two-sided confidence level, 0 < level < 1
  /// Noise type alpha to use at every tau instead of identifying it (--noise-type); must be in
  /// the estimator's domain (edf.hpp).
  std::optional<int> forced_alpha;
  /// Worker threads for the noise identification (0: all cores); results do not depend on it.
  unsigned threads = 0;
  /// Phase points of the whole record when `phase` is only its first part (the slice one MPI
  /// rank holds): the noise type is identified from `phase`, the EDF counts the whole record.
  /// 0: the record is `phase`.
  std::size_t n_phase_total = 0;
};

/// What was done at one point (same order as the points).
struct PointConfidence {
  NoiseId noise;     ///< how alpha was obtained (lag1_acf, b1..., forced, previous_tau, none)
  Edf edf;           ///< EDF and its method (greenhall_riley; ieee952_simple when no alpha)
  std::string note;  ///< empty when all went well; otherwise a sentence for the user
};

/// Sets edf, alpha, ci_low and ci_high of every point of an `estimator` curve computed from
/// `phase` (the same angle samples given to compute_deviation; only their count and values
/// matter, not tau0). Points are visited in increasing m: where the noise cannot be identified
/// (too few samples at the largest taus), the alpha of the next smaller tau is used, as Stable32
/// does (method previous_tau); when no smaller tau was identified either, the IEEE 952 rough EDF
/// N/m - 1 is used, labelled, and alpha stays unset (INT_MIN). tdev points get mdev's EDF (its
/// interval scales the same way).
/// Throws InputError for an impossible level, or a forced alpha outside the estimator's domain.
std::vector<PointConfidence> fill_confidence(std::vector<DevPoint>& points, Estimator estimator,
                                             std::span<const double> phase,
                                             const ConfidenceOptions& options = {});

/// Shorthand with the level and forced noise type as arguments.
std::vector<PointConfidence> fill_confidence(std::vector<DevPoint>& points, Estimator estimator,
                                             std::span<const double> phase, double level,
                                             std::optional<int> forced_alpha = std::nullopt);

}  // namespace imunoise
