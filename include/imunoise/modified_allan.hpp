#pragma once
// Modified Allan deviation (mdev) and time deviation (tdev).
//
// Input: N angle (phase) samples x spaced tau0 apart. For averaging factor m, tau = m tau0:
//
//   mod sigma^2(tau) = 1 / (2 m^2 tau^2 n) * sum_{j=0}^{n-1} ( sum_{i=j}^{j+m-1}
//                          (x[i+2m] - 2 x[i+m] + x[i]) )^2,       n = N - 3m + 1
//   tdev(tau) = tau / sqrt(3) * mdev(tau)     (an angle, in the rate unit times seconds)
//
// Domain: 1 <= m <= floor(N/3). Conventions of Stable32 and AllanTools; verified against the
// NBS14 published values (tests/core). The inner sums come from an exact long-double
// recursion restarted every 65536 terms, so cost is O(N) per factor.
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

std::vector<DevPoint> mdev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options = {});

std::vector<DevPoint> tdev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options = {});

}  // namespace imunoise
