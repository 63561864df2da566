#include "imunoise/study/work_budget.hpp"

#include <fmt/core.h>

#include "imunoise/theo.hpp"

namespace imunoise::study {

namespace {
constexpr double kTheoSecondsPerTerm = 0.13e-9;
}  // namespace

double fixed_seconds(Estimator estimator, std::size_t n_phase, TheoBrRatios ratios) {
  return estimator == Estimator::theobr ? theobr_bias_factor_terms(n_phase, ratios) * kTheoSecondsPerTerm
                                        : 0.0;
}

double estimated_seconds(Estimator estimator, std::size_t n_phase, std::size_t m) {
  const double n = static_cast<double>(n_phase);
  const double mm = static_cast<double>(m);
  switch (estimator) {
    case Estimator::mtotdev:
    case Estimator::ttotdev:
    case Estimator::htotdev:
      // (N - 3m + 1) subsequences of 6m window terms each.
      return n > 3.0 * mm ? (n - 3.0 * mm + 1.0) * 6.0 * mm * 0.1e-9 : 0.0;
    case Estimator::theo1:
    case Estimator::theobr:
      // (N - m) start points times m/2 spans.
      return n > mm ? (n - mm) * 0.5 * mm * kTheoSecondsPerTerm : 0.0;
    default:
      return 0.0;
  }
}

BudgetSplit split_by_budget(Estimator estimator, std::size_t n_phase,
                            std::span<const std::size_t> factors, double budget_s,
                            TheoBrRatios ratios) {
  BudgetSplit split;
  double total = fixed_seconds(estimator, n_phase, ratios);
  if (budget_s > 0.0 && total > budget_s) {  // nothing can be computed within the budget
    split.skipped.assign(factors.begin(), factors.end());
    split.skipped_seconds = total;
    for (const std::size_t m : factors) split.skipped_seconds += estimated_seconds(estimator, n_phase, m);
    split.fixed_cost_too_high = true;
    return split;
  }
  for (const std::size_t m : factors) {
    const double cost = estimated_seconds(estimator, n_phase, m);
    if (budget_s > 0.0 && (total + cost > budget_s || !split.skipped.empty())) {
      split.skipped.push_back(m);
      split.skipped_seconds += cost;
    } else {
      split.kept.push_back(m);
      total += cost;
    }
  }
  return split;
}

std::string duration_text(double seconds) {
  if (seconds >= 7200.0) return fmt::format("about {:.1f} h", seconds / 3600.0);
  if (seconds >= 120.0) return fmt::format("about {:.0f} min", seconds / 60.0);
  return fmt::format("about {:.0f} s", seconds);
}

}  // namespace imunoise::study
