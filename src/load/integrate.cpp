#include "imunoise/load/integrate.hpp"

#include <algorithm>

#include "imunoise/phase.hpp"

namespace imunoise::load {

double rate_offset(std::span<const double> rate_si) {
  return compensated_mean(rate_si.first(std::min(rate_si.size(), kRateOffsetSamples)));
}

std::vector<double> integrate_rate(std::span<const double> rate_si, double rate_hz) {
  return phase_from_rate(rate_si, 1.0 / rate_hz, rate_offset(rate_si));
}

}  // namespace imunoise::load
