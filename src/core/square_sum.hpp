#pragma once
// Sum of squares of v(i), i = 0..count-1, in four interleaved partial sums (lane j takes the
// i = j mod 4): the compiler turns the unrolled body into one 4-wide (or two 2-wide) vector
// accumulator, and the rounding is the same whatever the vector width, thread count or CPU.
#include <cstddef>

namespace imunoise::detail {

template <class Value>
inline double square_sum4(std::size_t count, Value&& v) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4) {
    const double a = v(i), b = v(i + 1), c = v(i + 2), d = v(i + 3);
    s0 += a * a;
    s1 += b * b;
    s2 += c * c;
    s3 += d * d;
  }
  for (; i < count; ++i) {
    const double a = v(i);
    s0 += a * a;
  }
  return (s0 + s1) + (s2 + s3);
}

}  // namespace imunoise::detail
