#pragma once
// Hadamard deviation, non-overlapping (hdev) and overlapping (ohdev): third differences of
// phase, insensitive to a linear rate drift (rate ramp), used for rate random walk and beyond.
//
// Input: N angle (phase) samples x spaced tau0 apart. For averaging factor m, tau = m tau0:
//
//   H sigma^2(tau) = 1 / (6 tau^2 n) * sum_k (x[k+3m] - 3 x[k+2m] + 3 x[k+m] - x[k])^2
//
//   ohdev: k = 0, 1, ..., N-3m-1          n = N - 3m
//   hdev:  k = 0, m, 2m, ..., k+3m<=N-1   n = floor((N-1)/m) - 2
//
// Domain: 1 <= m <= floor((N-1)/3). Conventions of Stable32 and AllanTools (NIST SP 1065
// eq. 17-18); verified against the NBS14 published values (tests/core). Cost as allan.hpp.
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

std::vector<DevPoint> hdev(std::span<const double> phase, double tau0_s,
                           std::span<const std::size_t> factors, const DevOptions& options = {});

std::vector<DevPoint> ohdev(std::span<const double> phase, double tau0_s,
                            std::span<const std::size_t> factors, const DevOptions& options = {});

}  // namespace imunoise
