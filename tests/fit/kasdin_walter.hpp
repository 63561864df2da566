#pragma once
// An independent noise generator for the fit tests: flicker rate noise made by the
// Kasdin-Walter fractional difference (1 - z^-1)^(-1/2) applied to white noise, i.e. a 1/f
// spectrum from the record length all the way to the Nyquist frequency (unlike the
// band-limited pole bank of src/sim), plus white and random-walk rate noise. Nothing here uses
// src/sim: the tests compare the fitter against a generator it was not developed with.
//
// Level of the flicker: the filter's gain |1 - e^{-i 2 pi f tau0}|^-1 = 1 / (2 sin(pi f tau0))
// turns white innovations of variance s^2 into the one-sided PSD s^2 / (pi f) at f << 1/tau0,
// i.e. h_-1 = s^2 / pi; the Allan variance of flicker rate noise is 2 ln 2 h_-1, and the
// eq. 5 floor is (2 ln 2 / pi) B^2: so innovations of standard deviation B give the floor B.
// (Kasdin, Proc. IEEE 83(5) 1995, eq. 122 for the impulse response h_k = h_{k-1} (k - 1/2)/k.)
//
// The convolution over the whole record is done by FFT (radix 2, zero-padded to at least 2n so
// it is linear, not circular). Two records share one complex transform (real and imaginary
// parts), the filter's spectrum is computed once per length.
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace imunoise::fit_test {

/// In-place iterative radix-2 FFT (sign -1 forward, +1 inverse without the 1/n).
inline void fft_radix2(std::vector<std::complex<double>>& a, int sign) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double ang = sign * 2.0 * std::numbers::pi / static_cast<double>(len);
    const std::size_t half = len / 2;
    // Twiddles of this stage computed directly (not by recurrence) to keep the error at 1e-16.
    std::vector<std::complex<double>> tw(half);
    for (std::size_t k = 0; k < half; ++k) tw[k] = std::polar(1.0, ang * static_cast<double>(k));
    for (std::size_t i = 0; i < n; i += len) {
      for (std::size_t k = 0; k < half; ++k) {
        const std::complex<double> u = a[i + k];
        const std::complex<double> v = a[i + k + half] * tw[k];
        a[i + k] = u + v;
        a[i + k + half] = u - v;
      }
    }
  }
}

/// Generator of Kasdin-Walter flicker sequences of a fixed length n.
class KasdinWalterFlicker {
 public:
  explicit KasdinWalterFlicker(std::size_t n) : n_(n) {
    size_ = 1;
    while (size_ < 2 * n_) size_ <<= 1;
    filter_.assign(size_, {0.0, 0.0});
    double h = 1.0;
    for (std::size_t k = 0; k < n_; ++k) {
      if (k > 0) h *= (static_cast<double>(k) - 0.5) / static_cast<double>(k);
      filter_[k] = {h, 0.0};
    }
    fft_radix2(filter_, -1);
  }

  /// Two independent flicker sequences (innovations of standard deviation sd) from rng.
  std::pair<std::vector<double>, std::vector<double>> pair(std::mt19937_64& rng, double sd) const {
    std::normal_distribution<double> gauss(0.0, sd);
    std::vector<std::complex<double>> a(size_, {0.0, 0.0});
    for (std::size_t i = 0; i < n_; ++i) a[i] = {gauss(rng), gauss(rng)};
    fft_radix2(a, -1);
    // The filter is real, so (W1 + i W2) H transforms back to y1 + i y2.
    for (std::size_t k = 0; k < size_; ++k) a[k] *= filter_[k];
    fft_radix2(a, +1);
    const double scale = 1.0 / static_cast<double>(size_);
    std::pair<std::vector<double>, std::vector<double>> out;
    out.first.resize(n_);
    out.second.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      out.first[i] = a[i].real() * scale;
      out.second[i] = a[i].imag() * scale;
    }
    return out;
  }

 private:
  std::size_t n_;
  std::size_t size_ = 1;
  std::vector<std::complex<double>> filter_;
};

/// Adds white rate noise (N, per sqrt(s)) and a rate random walk (K, per s^1.5) to `rate`
/// (samples spaced tau0_s), in place.
inline void add_white_and_random_walk(std::vector<double>& rate, double tau0_s, double n_coef,
                                      double k_coef, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double white_sd = n_coef / std::sqrt(tau0_s);
  const double step_sd = k_coef * std::sqrt(tau0_s);
  double walk = 0.0;
  for (double& r : rate) {
    walk += step_sd * gauss(rng);
    r += white_sd * gauss(rng) + walk;
  }
}

}  // namespace imunoise::fit_test
