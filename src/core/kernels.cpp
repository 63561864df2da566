#include "kernels.hpp"

// GCC builds an AVX2+FMA clone and a baseline one, picked by the loader (ifunc).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define IMUNOISE_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define IMUNOISE_CLONES
#endif

namespace imunoise::detail {

/// sum_{k<count} (x[k+2m] - 2 x[k+m] + x[k])^2
IMUNOISE_CLONES double sum_sq_second_difference(const double* x, std::size_t m,
                                                        std::size_t count) {
  const double* x0 = x;
  const double* x1 = x + m;
  const double* x2 = x + 2 * m;
  double sum = 0.0;
#pragma omp simd reduction(+ : sum)
  for (std::size_t k = 0; k < count; ++k) {
    const double d = x2[k] - 2.0 * x1[k] + x0[k];
    sum += d * d;
  }
  return sum;
}

/// sum_{k<count} (x[k+3m] - 3 x[k+2m] + 3 x[k+m] - x[k])^2
IMUNOISE_CLONES double sum_sq_third_difference(const double* x, std::size_t m,
                                                       std::size_t count) {
  const double* x0 = x;
  const double* x1 = x + m;
  const double* x2 = x + 2 * m;
  const double* x3 = x + 3 * m;
  double sum = 0.0;
#pragma omp simd reduction(+ : sum)
  for (std::size_t k = 0; k < count; ++k) {
    const double d = x3[k] - 3.0 * x2[k] + 3.0 * x1[k] - x0[k];
    sum += d * d;
  }
  return sum;
}

}  // namespace imunoise::detail
