#pragma once
// Estimators whose cost grows as N m per tau (mtotdev, ttotdev, htotdev, theo1) would run for
// hours at the longest taus of a long record; the command line keeps to a time budget instead
// and says what it left out. A policy of the study (dev, analyze), kept apart from the estimators.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "imunoise/estimator.hpp"
#include "imunoise/theo.hpp"

namespace imunoise::study {

/// Estimated wall time in seconds of one tau of `estimator` at factor m on n_phase phase points,
/// calibrated on the project's 2-core 2.3 GHz build machine (docs/performance.md: mtotdev
/// about 0.1 ns per window term, theo1 about 0.13 ns per term, with both cores). Zero for the
/// estimators that cost O(N) per tau.
double estimated_seconds(Estimator estimator, std::size_t n_phase, std::size_t m);

/// Estimated seconds an estimator spends once per curve, whatever the taus: ThêoBR's bias
/// factor (Theo1 at about N/6 factors); zero for the others.
double fixed_seconds(Estimator estimator, std::size_t n_phase, TheoBrRatios ratios);

struct BudgetSplit {
  std::vector<std::size_t> kept;     // ascending factors whose running total fits the budget
  std::vector<std::size_t> skipped;  // the rest
  double skipped_seconds = 0.0;      // their estimated cost
  bool fixed_cost_too_high = false;  // the per-curve cost alone exceeds the budget
};

/// Keeps factors (in the given ascending order) while their cumulative estimated cost stays
/// within budget_s; budget_s <= 0 keeps everything.
BudgetSplit split_by_budget(Estimator estimator, std::size_t n_phase,
                            std::span<const std::size_t> factors, double budget_s,
                            TheoBrRatios ratios = TheoBrRatios::taylor_howe);

/// "about 2.1 h", "about 40 min", "about 12 s".
std::string duration_text(double seconds);

}  // namespace imunoise::study
