#pragma once
// The simulated TG-100 gyro 1 of the paper (Table 2) for the fit tests, in deg/s.
#include <cstdint>
#include <vector>

#include "imunoise/phase.hpp"
#include "imunoise/sim/generator.hpp"

namespace imunoise::fit_test {

inline constexpr double kRateHz = 200.0;
inline constexpr double kN = 8.9e-4;   // deg/sqrt(s)
inline constexpr double kB = 5.9e-4;   // deg/s
inline constexpr double kK = 1.5e-5;   // deg/s/sqrt(s)

inline sim::NoiseModel tg100_gyro1() {
  sim::NoiseModel model;
  model.n_unit_sqrt_s = kN;
  model.b_unit = kB;
  model.k_unit_per_sqrt_s = kK;
  return model;
}

/// Angle samples (deg) of a record of `hours` at 200 Hz.
inline std::vector<double> tg100_phase(double hours, std::uint64_t seed) {
  const auto n = static_cast<std::size_t>(hours * 3600.0 * kRateHz);
  const auto rate = sim::simulate(tg100_gyro1(), kRateHz, n, seed);
  return phase_from_rate(rate, 1.0 / kRateHz, 0.0);
}

}  // namespace imunoise::fit_test
