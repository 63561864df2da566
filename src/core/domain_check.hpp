#pragma once
// Input checks shared by every estimator: a usable sample interval, factors in the domain.
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"

namespace imunoise::detail {

inline void check_factors(Estimator estimator, std::span<const double> phase, double tau0_s,
                          std::span<const std::size_t> factors) {
  if (!(tau0_s > 0.0) || !std::isfinite(tau0_s)) {
    throw InputError("the sample interval must be positive and finite, got " +
                     fmt::format("{:g}", tau0_s) + " s; check --rate");
  }
  const std::size_t max_m = max_averaging_factor(estimator, phase.size());
  for (const std::size_t m : factors) {
    if (m == 0 || m > max_m) {
      throw InputError(std::string(estimator_name(estimator)) + ": averaging factor m = " +
                       std::to_string(m) + " is outside the domain 1.." + std::to_string(max_m) +
                       " for " + std::to_string(phase.size()) + " phase samples");
    }
    if (requires_even_factor(estimator) && m % 2 != 0) {
      throw InputError(std::string(estimator_name(estimator)) + ": averaging factor m = " +
                       std::to_string(m) + " must be even (tau = 0.75 m tau0)");
    }
  }
}

}  // namespace imunoise::detail
