#include "imunoise/phase.hpp"

#include <algorithm>
#include <cmath>

#include "kernels.hpp"

namespace imunoise {

using detail::neumaier_add;

double compensated_mean(std::span<const double> values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  double compensation = 0.0;
  for (const double v : values) neumaier_add(sum, compensation, v);
  return (sum + compensation) / static_cast<double>(values.size());
}

PhaseIntegrator::PhaseIntegrator(double tau0_s, double offset) : tau0_s_(tau0_s), offset_(offset) {}

void PhaseIntegrator::push(std::span<const double> rate, std::vector<double>& out) {
  if (!started_) {
    out.push_back(0.0);
    started_ = true;
  }
  // Through a small buffer and insert, not resize: resize would zero the fresh pages once more
  // before they are written (the reserved phase of a long record is its largest array).
  out.reserve(out.size() + rate.size());
  constexpr std::size_t kChunk = 2048;
  double buffer[kChunk];
  for (std::size_t i = 0; i < rate.size(); i += kChunk) {
    const std::size_t n = std::min(kChunk, rate.size() - i);
    detail::compensated_prefix(rate.data() + i, n, offset_, tau0_s_, sum_, compensation_, buffer);
    out.insert(out.end(), buffer, buffer + n);
  }
}

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s, double offset) {
  std::vector<double> phase;
  phase.reserve(rate.size() + 1);
  PhaseIntegrator integrator(tau0_s, offset);
  integrator.push(rate, phase);
  return phase;
}

}  // namespace imunoise
