#include "kernels.hpp"

// GCC builds AVX-512, AVX2+FMA and baseline clones, picked by the loader (ifunc).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define IMUNOISE_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define IMUNOISE_CLONES
#endif

// The 64-byte vector type only crosses always-inline helpers, never a real call boundary, so
// GCC's note that its ABI would differ without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace imunoise::detail {
namespace {

// Four independent accumulators of eight lanes: a single accumulator would serialise on the
// latency of the add. Eight lanes are one AVX-512 register, two AVX2 ones, four SSE2 ones:
// each clone gets the widest operations it has.
typedef double Vec8 __attribute__((vector_size(64)));
constexpr std::size_t kLanes = 8;
static_assert(sizeof(Vec8) == kLanes * sizeof(double));
constexpr std::size_t kUnroll = 4;

__attribute__((always_inline)) inline Vec8 load(const double* p) {
  Vec8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

__attribute__((always_inline)) inline double horizontal_sum(const Vec8 (&acc)[kUnroll]) {
  const Vec8 s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

// Sum of squares of a finite difference of order 2 or 3. No lambdas or non-inlined helpers:
// in a target_clones function every callee must be inlined, or a 64-byte vector would cross a
// call between code built for different instruction sets (it does at -O0 otherwise).
template <int Order>
__attribute__((always_inline)) inline double sum_sq_difference(const double* x, std::size_t m,
                                                                std::size_t count) {
  const double* x0 = x;
  const double* x1 = x + m;
  const double* x2 = x + 2 * m;
  const double* x3 = x + 3 * m;
  Vec8 acc[kUnroll] = {};
  std::size_t k = 0;
  for (; k + kLanes * kUnroll <= count; k += kLanes * kUnroll) {
    for (std::size_t u = 0; u < kUnroll; ++u) {
      const std::size_t i = k + u * kLanes;
      Vec8 d;
      if constexpr (Order == 2) {
        d = load(x2 + i) - 2.0 * load(x1 + i) + load(x0 + i);
      } else {
        d = load(x3 + i) - 3.0 * load(x2 + i) + 3.0 * load(x1 + i) - load(x0 + i);
      }
      acc[u] += d * d;
    }
  }
  double sum = horizontal_sum(acc);
  for (; k < count; ++k) {
    double d;
    if constexpr (Order == 2) {
      d = x2[k] - 2.0 * x1[k] + x0[k];
    } else {
      d = x3[k] - 3.0 * x2[k] + 3.0 * x1[k] - x0[k];
    }
    sum += d * d;
  }
  return sum;
}

}  // namespace

IMUNOISE_CLONES double sum_sq_second_difference(const double* x, std::size_t m,
                                                std::size_t count) {
  return sum_sq_difference<2>(x, m, count);
}

IMUNOISE_CLONES double sum_sq_third_difference(const double* x, std::size_t m,
                                               std::size_t count) {
  return sum_sq_difference<3>(x, m, count);
}

}  // namespace imunoise::detail
