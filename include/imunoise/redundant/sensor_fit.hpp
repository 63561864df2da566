#pragma once
// A sensor's noise model straight from its recording, as `imunoise fit` would identify it
// (overlapping Allan deviation on the octave grid, weighted least squares of Q, N, B, K with
// 95% intervals): what the fusion weights and the fault detector need when no fit documents
// are given. Cost ~0.5 s for a 6 h, 200 Hz record (docs/fit.md).
#include <span>
#include <string>

#include "imunoise/redundant/analysis.hpp"

namespace imunoise::redundant {

/// `rate_rad_s` are rate samples in rad/s at `rate_hz`. InputError naming `source` when the
/// record cannot be fitted (constant, too short).
SensorModel fit_sensor_model(std::span<const double> rate_rad_s, double rate_hz, const std::string& source);

}  // namespace imunoise::redundant
