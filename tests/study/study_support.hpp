#pragma once
// Records with known noise for the study tests.
#include <string>
#include <vector>

#include "imunoise/phase.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/units.hpp"

namespace imunoise::test {

/// A simulated gyro in deg/s: white noise N and rate random walk K (deg units), `seconds` long.
inline study::Record simulated_gyro(const std::string& name, double n, double k, double rate_hz,
                                    double seconds, std::uint64_t seed,
                                    const std::string& unit_name = "deg/s") {
  sim::NoiseModel model;
  model.n_unit_sqrt_s = n;
  model.k_unit_per_sqrt_s = k;
  auto y = sim::simulate(model, rate_hz, static_cast<std::size_t>(seconds * rate_hz), seed);
  const Unit unit = parse_unit(unit_name);
  for (double& v : y) v *= parse_unit("deg/s").to_si;  // the model is in deg/s
  study::Record r;
  r.name = name;
  r.source = name + ".csv";
  r.rate_hz = rate_hz;
  r.n_samples = y.size();
  r.phase_si = phase_from_rate(y, 1.0 / rate_hz, compensated_mean(y));
  r.rate_unit = unit;
  r.unit_given = true;
  return r;
}

}  // namespace imunoise::test
