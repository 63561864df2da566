#pragma once
// Time-error statistics of the phase (angle) itself: MTIE and TIE rms (ITU-T G.810; NIST
// SP 1065 sec. 5.2.16-5.2.17). Unlike the deviations they see a constant rate offset: the phase
// integrated from rate by phase_from_rate has the mean rate removed (as Stable32's PHASE.DAT).
//
// Input: N angle samples x[0..N-1] spaced tau0 apart; tau = m tau0; results in the angle unit.
//   mtie(m)   = max over windows of m+1 points x[i..i+m] of (max - min), i = 0..N-m-1
//   tierms(m) = sqrt( 1/(N-m) sum_{i=0}^{N-m-1} (x[i+m] - x[i])^2 )
// Domain: 1 <= m <= N-1; n = N - m. (Stable32 steps the MTIE factors 1, 3, 7, 15, ...; any m is
// allowed here, with the same window-of-m+1-points meaning.)
// Algorithm: MTIE by monotonic queues of the window maximum and minimum, O(N) per factor
// whatever m is (the literal definition is O(N m)); TIE rms one pass, O(N) per factor. Factors
// are spread over threads. Accuracy: exact (max/min) and correctly summed differences.
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

std::vector<DevPoint> mtie(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options = {});

std::vector<DevPoint> tierms(std::span<const double> phase, double tau0_s,
                             std::span<const std::size_t> factors, const DevOptions& options = {});

}  // namespace imunoise
