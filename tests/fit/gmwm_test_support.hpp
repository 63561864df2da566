#pragma once
// An independent generator for the GMWM tests (no src/sim code): white rate noise, a
// point-sampled random walk and AR1 processes by their exact recursion, from a 64-bit
// splitmix/xorshift generator and the Box-Muller transform written here.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "imunoise/allan.hpp"

namespace imunoise::gmwm_test {

class Normals {
 public:
  // The seed is hashed (one splitmix64 output) so that seeds s and s + 1 give unrelated streams
  // (a plain multiple of the increment would shift one stream by one draw).
  explicit Normals(std::uint64_t seed) {
    std::uint64_t z = seed + 0x632BE59BD9B4E019ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    state_ = z ^ (z >> 31);
  }
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = 0.0;
    do u1 = uniform(); while (u1 <= 0.0);
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  double uniform() {  // splitmix64 -> [0, 1)
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  std::uint64_t state_ = 0;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

struct Ar1Spec {
  double sigma = 0.0;  // stationary sd (rate unit)
  double tc_s = 0.0;   // correlation time
};

/// Rate samples: white (N, per-sample sd N / sqrt(tau0)) + random walk (increments of sd
/// K sqrt(tau0), started at 0) + each AR1 (y_k = phi y_{k-1} + sigma sqrt(1 - phi^2) e_k,
/// started stationary).
inline std::vector<double> make_rate(std::size_t n, double tau0_s, double n_coef, double k_coef,
                                     const std::vector<Ar1Spec>& ar1, std::uint64_t seed) {
  Normals normal(seed);
  std::vector<double> y(n, 0.0);
  const double white = n_coef / std::sqrt(tau0_s);
  const double step = k_coef * std::sqrt(tau0_s);
  double rw = 0.0;
  std::vector<double> state(ar1.size()), phi(ar1.size()), innov(ar1.size());
  for (std::size_t g = 0; g < ar1.size(); ++g) {
    phi[g] = std::exp(-tau0_s / ar1[g].tc_s);
    innov[g] = ar1[g].sigma * std::sqrt(1.0 - phi[g] * phi[g]);
    state[g] = ar1[g].sigma * normal();
  }
  for (std::size_t i = 0; i < n; ++i) {
    double v = white * normal();
    if (k_coef > 0.0) {
      rw += step * normal();
      v += rw;
    }
    for (std::size_t g = 0; g < ar1.size(); ++g) {
      state[g] = phi[g] * state[g] + innov[g] * normal();
      v += state[g];
    }
    y[i] = v;
  }
  return y;
}

/// Phase (x_0 = 0, x_k = tau0 sum of the first k rates, mean rate removed) and its oadev at the
/// octave factors m = 1, 2, 4, ... with 2 m < n_phase (the phase has rate.size() + 1 samples).
inline std::vector<DevPoint> octave_points(const std::vector<double>& rate, double tau0_s) {
  double mean = 0.0;
  for (double v : rate) mean += v;
  mean /= static_cast<double>(rate.size());
  std::vector<double> phase(rate.size() + 1, 0.0);
  long double acc = 0.0L;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    acc += static_cast<long double>((rate[i] - mean) * tau0_s);
    phase[i + 1] = static_cast<double>(acc);
  }
  std::vector<std::size_t> m;
  for (std::size_t f = 1; 2 * f < phase.size(); f *= 2) m.push_back(f);
  return oadev(phase, tau0_s, m);
}

/// The same curve as (m, avar) for fit_gmwm.
struct Curve {
  std::vector<std::size_t> m;
  std::vector<double> avar;
  std::size_t n_phase = 0;
};
inline Curve curve_of(const std::vector<DevPoint>& points, std::size_t n_phase) {
  Curve c;
  c.n_phase = n_phase;
  for (const auto& p : points) {
    c.m.push_back(p.m);
    c.avar.push_back(p.dev * p.dev);
  }
  return c;
}
inline Curve octave_curve(const std::vector<double>& rate, double tau0_s) {
  return curve_of(octave_points(rate, tau0_s), rate.size() + 1);
}

}  // namespace imunoise::gmwm_test
