#pragma once
// The NBS14 test vectors (NIST SP 1065), built from their definitions.
#include <cstdint>
#include <vector>

namespace imunoise::test {

/// The 9 fractional-frequency values of the 10-point set.
inline std::vector<double> nbs14_10_point_frequency() {
  return {892, 809, 823, 798, 671, 644, 883, 903, 677};
}

/// The 1000-point set: Lehmer generator n0 = 1234567890, n_{i+1} = 16807 n_i mod (2^31 - 1),
/// y_i = n_i / (2^31 - 1), i = 0..999 (fractional frequency, tau0 = 1 s).
inline std::vector<double> nbs14_1000_point_frequency() {
  std::vector<double> y;
  std::uint64_t n = 1234567890;
  for (int i = 0; i < 1000; ++i) {
    y.push_back(static_cast<double>(n) / 2147483647.0);
    n = (16807 * n) % 2147483647;
  }
  return y;
}

/// Stable32's PHASE.DAT: the 1000-point set integrated to phase about its mean (long double
/// sums), x0 = 0: 1001 phase points in seconds at tau0 = 1 s (references.md).
inline std::vector<double> nbs14_phase_dat() {
  const auto y = nbs14_1000_point_frequency();
  long double mean = 0;
  for (double v : y) mean += v;
  mean /= static_cast<long double>(y.size());
  std::vector<double> x{0.0};
  long double sum = 0;
  for (double v : y) {
    sum += v - mean;
    x.push_back(static_cast<double>(sum));
  }
  return x;
}

}  // namespace imunoise::test
