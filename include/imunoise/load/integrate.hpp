#pragma once
// The one step from rate samples to the phase every estimator works on: the rate offset
// removed before integration is the compensated mean of the first kRateOffsetSamples samples.
// Every estimator cancels a constant rate exactly, so the offset only keeps the phase small (no
// cancellation); taking it from a prefix lets a file be integrated in one streaming pass, and
// lets each MPI rank integrate its slice from the offset rank 0 read, joining exactly.
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::load {

inline constexpr std::size_t kRateOffsetSamples = std::size_t{1} << 20;

/// The offset removed from rate samples (SI) before integration.
double rate_offset(std::span<const double> rate_si);

/// N rate samples (SI) at rate_hz -> N + 1 phase samples (phase_from_rate with rate_offset).
std::vector<double> integrate_rate(std::span<const double> rate_si, double rate_hz);

}  // namespace imunoise::load
