#include "imunoise/parallel/distributed_fit.hpp"

#include <string>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/parallel/distributed_deviations.hpp"
#include "imunoise/study/fit_stage.hpp"

namespace imunoise::parallel {

std::optional<std::pair<Record, std::vector<study::Curve>>> curves_distributed(Ranks& ranks,
                                                                               const load::LoadOptions& input,
                                                                               const study::CurveOptions& options) {
  if (options.bias_correct) throw InputError("--bias-correct does not apply to --mpi's estimators");
  auto dist = distributed_deviations(ranks, input, options.estimators, options.grid);
  if (!dist.root) return std::nullopt;
  const std::string note =
      options.no_ci ? "--mpi: sums merged over the ranks; no confidence intervals (--no-ci)"
                    : "--mpi: sums merged over the ranks; noise type identified on rank 0's slice (" +
                          std::to_string(dist.root_phase_si.size()) + " of " + std::to_string(dist.n_phase) +
                          " phase points), EDF over the whole record";
  auto curves = study::curves_from_points(dist.record, options, dist.curves, dist.root_phase_si, dist.n_phase, note);
  return std::make_pair(std::move(dist.record), std::move(curves));
}

std::optional<std::pair<Record, fit::FitResult>> fit_distributed(Ranks& ranks, const load::LoadOptions& input,
                                                                 const TauGrid& grid, const fit::FitOptions& options) {
  auto dist = distributed_deviations(ranks, input, {Estimator::oadev}, grid);
  if (!dist.root) return std::nullopt;
  bool constant = true;
  for (const auto& p : dist.curves[0]) constant = constant && !(p.n > 0 && p.dev > 0.0);
  if (constant) {
    throw InputError(dist.record.source + ": the rate is constant (all-zero or a fixed value): there "
                     "is no noise to identify; check --column and the file");
  }
  const std::vector<std::string> warnings{
      "--mpi: the record checks (quantization, saturation, constant stretches) need the whole "
      "record in one place and were not run"};
  auto result = study::fit_curve(dist.record, dist.curves[0], dist.n_phase, options, warnings);
  return std::make_pair(std::move(dist.record), std::move(result));
}

}  // namespace imunoise::parallel
