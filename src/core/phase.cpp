#include "imunoise/phase.hpp"

#include <cmath>

namespace imunoise {
namespace {

// Neumaier's compensated addition: sum + compensation carries the exact running total to
// about one ulp, so the integral stays correct over 1e9 samples.
inline void neumaier_add(double& sum, double& compensation, double value) {
  const double t = sum + value;
  if (std::abs(sum) >= std::abs(value)) {
    compensation += (sum - t) + value;
  } else {
    compensation += (value - t) + sum;
  }
  sum = t;
}

}  // namespace

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
  const std::size_t base = out.size();
  out.resize(base + rate.size());
  double* dst = out.data() + base;
  double sum = sum_;
  double compensation = compensation_;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    neumaier_add(sum, compensation, rate[i] - offset_);
    dst[i] = (sum + compensation) * tau0_s_;
  }
  sum_ = sum;
  compensation_ = compensation;
}

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s, double offset) {
  std::vector<double> phase;
  phase.reserve(rate.size() + 1);
  PhaseIntegrator integrator(tau0_s, offset);
  integrator.push(rate, phase);
  return phase;
}

}  // namespace imunoise
