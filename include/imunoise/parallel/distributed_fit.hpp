#pragma once
// The curves (`dev --mpi`) and the noise-model fit (`fit --mpi`) of one record sliced over the
// ranks. Curves: the mergeable sums merged, the noise type behind each interval identified on
// rank 0's own slice (the whole record never gathers in one place), the EDF over every sample.
// Fit: the oadev sums merged
// in a tree (distributed_deviations.hpp) and the merged curve fitted on rank 0
// (study::fit_curve). The record checks that need the whole record in one place
// (quantization, saturation, constant stretches) are not run, which a warning says; a constant
// rate is refused, as the serial fit refuses it.
#include <optional>
#include <utility>
#include <vector>

#include "imunoise/fit/fit.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/parallel/ranks.hpp"
#include "imunoise/study/curves.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::parallel {

/// The record's description and its curves on rank 0; nullopt on the other ranks. InputError
/// for an estimator that cannot be merged or an option that does not apply (bias correction).
std::optional<std::pair<Record, std::vector<study::Curve>>> curves_distributed(Ranks& ranks,
                                                                               const load::LoadOptions& input,
                                                                               const study::CurveOptions& options);

/// The record's description and its fit on rank 0; nullopt on the other ranks.
std::optional<std::pair<Record, fit::FitResult>> fit_distributed(Ranks& ranks, const load::LoadOptions& input,
                                                                 const TauGrid& grid, const fit::FitOptions& options);

}  // namespace imunoise::parallel
