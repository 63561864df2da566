#pragma once
// Shared fixtures of the preprocessing tests.
#include <cstddef>
#include <random>
#include <vector>

namespace imunoise::preprocess::test {

/// n samples of seeded Gaussian white noise of standard deviation sigma.
inline std::vector<double> white(std::size_t n, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<double> v(n);
  for (auto& x : v) x = g(rng);
  return v;
}

}  // namespace imunoise::preprocess::test
