#pragma once
// From rate samples to angle (phase) samples, the form every estimator works on.
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise {

/// Integrates N rate samples y (unit U) into N+1 angle samples x (unit U*s):
///   x[0] = 0,  x[k] = tau0_s * sum_{i<k} (y[i] - offset).
/// Every Allan/Hadamard-type estimator uses differences of order >= 2 of x, which cancel a
/// constant rate, so any offset gives the same deviations; passing the mean keeps x small and
/// the differences free of cancellation (a rate offset 1e4 times the noise changes results by
/// less than 1e-12 relative). The running total is compensated (its roundings carried by an
/// error-free two-sum, eight samples at a time), so x[k] is the integral to within a few ulp of
/// itself plus a few ulp of a sum of at most eight samples, for any N.
std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s, double offset);

/// Mean of the samples with compensated summation (exact to a few ulp); 0 for an empty span.
double compensated_mean(std::span<const double> values);

/// Incremental form of phase_from_rate for data that arrives in chunks: the concatenation of
/// what push() appends equals phase_from_rate over the concatenated input (to rounding).
class PhaseIntegrator {
 public:
  PhaseIntegrator(double tau0_s, double offset);
  /// Appends the angle samples that follow `rate` to `out` (the first call also emits x[0] = 0).
  void push(std::span<const double> rate, std::vector<double>& out);

 private:
  double tau0_s_;
  double offset_;
  double sum_ = 0.0;
  double compensation_ = 0.0;
  bool started_ = false;
};

}  // namespace imunoise
