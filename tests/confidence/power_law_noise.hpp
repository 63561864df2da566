#pragma once
// Test helper: pure power-law noise with fixed seeds, the same on every platform.
//
// Gaussian deviates: std::mt19937_64 (fully specified by the standard) and our own Box-Muller
// transform (std::normal_distribution's algorithm is implementation-defined).
// Flicker noise: the Kasdin-Walter fractional-difference filter, y_n = sum_{k=0}^{n} h_k w_{n-k},
// h_0 = 1, h_k = h_{k-1} (k - 1/2) / k (PSD ~ 1/f), started from a zero past; it is applied by
// direct convolution (O(n^2), fine for the few thousand points used here).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace imunoise::test {

class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : engine_(seed) {}

  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    // Uniforms in (0, 1]: 53 random bits, never 0 (log(0) excluded).
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * 3.14159265358979323846 * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

inline std::vector<double> white_noise(std::size_t n, double sigma, Gaussian& gaussian) {
  std::vector<double> v(n);
  for (double& x : v) x = sigma * gaussian();
  return v;
}

/// x[0] = 0, x[k] = sum_{i<k} y[i]: n + 1 points (tau0 = 1).
inline std::vector<double> integrate(const std::vector<double>& y) {
  std::vector<double> x(y.size() + 1, 0.0);
  for (std::size_t i = 0; i < y.size(); ++i) x[i + 1] = x[i] + y[i];
  return x;
}

/// Running sum y[k] = sum_{i<=k} w[i] (n points).
inline std::vector<double> running_sum(const std::vector<double>& w) {
  std::vector<double> y(w.size());
  double s = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) y[i] = (s += w[i]);
  return y;
}

/// Kasdin-Walter flicker filter coefficients h_0..h_{n-1}.
inline std::vector<double> flicker_coefficients(std::size_t n) {
  std::vector<double> h(n);
  if (n == 0) return h;
  h[0] = 1.0;
  for (std::size_t k = 1; k < n; ++k) {
    h[k] = h[k - 1] * (static_cast<double>(k) - 0.5) / static_cast<double>(k);
  }
  return h;
}

/// Flicker noise from unit white noise w: y = h * w (causal convolution, zero past).
inline std::vector<double> flicker_noise(const std::vector<double>& h, double sigma,
                                         Gaussian& gaussian) {
  const std::size_t n = h.size();
  const std::vector<double> w = white_noise(n, sigma, gaussian);
  std::vector<double> y(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (std::size_t k = 0; k <= i; ++k) s += h[k] * w[i - k];
    y[i] = s;
  }
  return y;
}

/// n_phase phase (angle) samples of pure power-law noise alpha in -4..2 (tau0 = 1), unit
/// driving noise. PM types are made as phase; FM types as rate integrated to phase.
inline std::vector<double> power_law_phase(int alpha, std::size_t n_phase, Gaussian& gaussian) {
  const std::size_t n_rate = n_phase - 1;
  switch (alpha) {
    case 2:
      return white_noise(n_phase, 1.0, gaussian);
    case 1:
      return flicker_noise(flicker_coefficients(n_phase), 1.0, gaussian);
    case 0:
      return integrate(white_noise(n_rate, 1.0, gaussian));
    case -1:
      return integrate(flicker_noise(flicker_coefficients(n_rate), 1.0, gaussian));
    case -2:
      return integrate(running_sum(white_noise(n_rate, 1.0, gaussian)));
    case -3:
      return integrate(running_sum(flicker_noise(flicker_coefficients(n_rate), 1.0, gaussian)));
    case -4:
      return integrate(running_sum(running_sum(white_noise(n_rate, 1.0, gaussian))));
    default:
      return {};
  }
}

}  // namespace imunoise::test
