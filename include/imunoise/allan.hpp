#pragma once
// Allan deviation, non-overlapping (adev) and overlapping (oadev).
//
// Input: N angle (phase) samples x[0..N-1] spaced tau0 apart (phase_from_rate turns N-1 rate
// samples into N angle samples). For averaging factor m and tau = m * tau0:
//
//   sigma^2(tau) = 1 / (2 tau^2 n) * sum_k (x[k+2m] - 2 x[k+m] + x[k])^2
//
//   oadev: k = 0, 1, ..., N-2m-1        n = N - 2m          (the paper's eq. 3, IEEE 952 C)
//   adev:  k = 0, m, 2m, ..., k+2m<=N-1 n = floor((N-1)/m) - 1
//
// Domain: 1 <= m <= floor((N-1)/2) (at least one term). Conventions match Stable32 and
// AllanTools; verified against the NBS14 published values to 6e-7 relative (tests/core).
// Accuracy: terms are formed in double from phase that is correctly rounded (phase.hpp), and
// summed in blocks then in long double; a rate offset 1e4 times the noise changes results by
// less than 1e-9 relative. Cost: one fused pass over x for all factors, O(N) per factor.
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

std::vector<DevPoint> adev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options = {});

std::vector<DevPoint> oadev(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options = {});

}  // namespace imunoise
