#pragma once
// Finding the first NaN or infinity in a record, at memory speed: every entry point checks its
// whole input before analysis, so this scan must cost far less than the analysis itself.
#include <cstddef>
#include <span>

namespace imunoise {

/// Index of the first non-finite value in values, or values.size() when all are finite.
/// Scans blocks with a vectorizable reduction (x - x is NaN exactly for NaN and +-Inf) and
/// looks inside a block only when it holds a non-finite value. threads: 0 = all cores.
std::size_t first_non_finite(std::span<const double> values, unsigned threads = 1);

}  // namespace imunoise
