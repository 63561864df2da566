#pragma once
// Test helper: random-walk phase (white FM) riding on a large constant and linear offset, plus
// optional white phase noise — the cancellation guard for fast algorithms against their
// literal definitions. std::normal_distribution differs between standard libraries, which is
// fine here: the tests compare two computations on the same data, not fixed numbers.
#include <cstddef>
#include <random>
#include <vector>

namespace imunoise::test {

inline std::vector<double> offset_random_walk(std::size_t n, unsigned seed, double offset,
                                              double slope, double white_sd = 0.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(n);
  double s = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    s += g(rng);
    x[k] = offset + slope * static_cast<double>(k) + s;
    if (white_sd > 0.0) x[k] += white_sd * g(rng);
  }
  return x;
}

}  // namespace imunoise::test
