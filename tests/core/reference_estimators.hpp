#pragma once
// Straightforward transcriptions of the estimator definitions (NIST SP 1065 eqs. 8, 14, 17-18),
// in long double, kept deliberately naive: the engine is checked against them.
#include <cmath>
#include <cstddef>
#include <vector>

#include "imunoise/estimator.hpp"

namespace imunoise::test {

inline double reference_deviation(Estimator estimator, const std::vector<double>& x, double tau0,
                                  std::size_t m) {
  const std::size_t N = x.size();
  const long double tau = static_cast<long double>(m) * tau0;
  long double sum = 0.0L;
  std::size_t n = 0;
  auto d2 = [&](std::size_t k) {
    return static_cast<long double>(x[k + 2 * m]) - 2.0L * x[k + m] + x[k];
  };
  auto d3 = [&](std::size_t k) {
    return static_cast<long double>(x[k + 3 * m]) - 3.0L * x[k + 2 * m] + 3.0L * x[k + m] - x[k];
  };
  switch (estimator) {
    case Estimator::adev:
    case Estimator::oadev: {
      const std::size_t stride = estimator == Estimator::adev ? m : 1;
      for (std::size_t k = 0; k + 2 * m < N; k += stride, ++n) sum += d2(k) * d2(k);
      return static_cast<double>(std::sqrt(sum / (2.0L * n)) / tau);
    }
    case Estimator::hdev:
    case Estimator::ohdev: {
      const std::size_t stride = estimator == Estimator::hdev ? m : 1;
      for (std::size_t k = 0; k + 3 * m < N; k += stride, ++n) sum += d3(k) * d3(k);
      return static_cast<double>(std::sqrt(sum / (6.0L * n)) / tau);
    }
    case Estimator::mdev:
    case Estimator::tdev: {
      for (std::size_t j = 0; j + 3 * m <= N; ++j, ++n) {
        long double inner = 0.0L;
        for (std::size_t i = j; i < j + m; ++i) inner += d2(i);
        sum += inner * inner;
      }
      const long double mdev = std::sqrt(sum / (2.0L * m * m * n)) / tau;
      return static_cast<double>(estimator == Estimator::tdev ? mdev * tau / std::sqrt(3.0L)
                                                              : mdev);
    }
    default:  // the total, Theo and time-error families: reference_total.hpp
      break;
  }
  return NAN;
}

}  // namespace imunoise::test
