#pragma once
// The noise-model fit of one record sliced over the ranks (`fit --mpi`): the oadev sums merged
// in a tree (distributed_deviations.hpp) and the merged curve fitted on rank 0
// (study::fit_curve). The record checks that need the whole record in one place
// (quantization, saturation, constant stretches) are not run, which a warning says; a constant
// rate is refused, as the serial fit refuses it.
#include <optional>
#include <utility>

#include "imunoise/fit/fit.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/parallel/ranks.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::parallel {

/// The record's description and its fit on rank 0; nullopt on the other ranks.
std::optional<std::pair<Record, fit::FitResult>> fit_distributed(Ranks& ranks, const load::LoadOptions& input,
                                                                 const TauGrid& grid, const fit::FitOptions& options);

}  // namespace imunoise::parallel
