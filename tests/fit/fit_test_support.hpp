#pragma once
// The simulated TG-100 gyro 1 of the paper (Table 2) for the fit tests, in deg/s.
#include <cstdint>
#include <vector>

#include "imunoise/allan.hpp"
#include "imunoise/fit/fit.hpp"
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

/// The fit of a phase record's oadev curve on the octave grid, after the record checks
/// (all-zero, constant, quantized, saturated) that the library's Record fit runs too.
inline fit::FitResult fit_phase(std::span<const double> phase_si, double tau0_s,
                                const fit::FitOptions& options = {}) {
  const std::size_t n = phase_si.size();
  const auto warnings = fit::record_warnings(phase_si, tau0_s);
  if (fit::is_constant_record(phase_si, tau0_s)) {
    const DevPoint zero{1, tau0_s, 0.0};
    fit::FitResult r = fit::fit_allan(std::span<const DevPoint>(&zero, 1), n, tau0_s, options);
    r.summary.warnings = warnings;
    return r;
  }
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; 2 * m < n; m *= 2) factors.push_back(m);
  const auto points = oadev(phase_si, tau0_s, factors);
  fit::FitResult result = fit::fit_allan(points, n, tau0_s, options);
  result.summary.warnings.insert(result.summary.warnings.begin(), warnings.begin(), warnings.end());
  return result;
}

}  // namespace imunoise::fit_test
