// Robust Haar wavelet variance: Tukey-biweight M-estimate of scale (robust_wavelet.hpp).
#include "imunoise/fit/robust_wavelet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::fit {
namespace {

double rho(double u, double c) {
  const double v = u / c;
  if (std::abs(v) >= 1.0) return 1.0;
  const double w = 1.0 - v * v;
  return 1.0 - w * w * w;
}

double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

/// int_0^c f(z) phi(z) dz by composite Simpson (the integrands are polynomials times phi).
template <class F>
double simpson_0c(F f, double c) {
  constexpr int steps = 4000;
  const double h = c / steps;
  double sum = f(0.0) * normal_pdf(0.0) + f(c) * normal_pdf(c);
  for (int i = 1; i < steps; ++i) {
    const double z = i * h;
    sum += (i % 2 ? 4.0 : 2.0) * f(z) * normal_pdf(z);
  }
  return sum * h / 3.0;
}

struct Moments {
  double delta, var_rho, z_drho;
};

Moments moments(double c) {
  const double tail = std::erfc(c / std::numbers::sqrt2);  // P(|Z| > c)
  const double delta = 2.0 * simpson_0c([&](double z) { return rho(z, c); }, c) + tail;
  const double var = 2.0 * simpson_0c([&](double z) { const double d = rho(z, c) - delta; return d * d; }, c) +
                     (1.0 - delta) * (1.0 - delta) * tail;
  // z rho'(z) = 6 (z/c)^2 (1 - (z/c)^2)^2 inside, 0 outside.
  const double zd = 2.0 * simpson_0c([&](double z) { const double v = z / c, w = 1.0 - v * v; return 6.0 * v * v * w * w; }, c);
  return {delta, var, zd};
}

}  // namespace

double biweight_scale_efficiency(double c) {
  const Moments m = moments(c);
  return m.z_drho * m.z_drho / (2.0 * m.var_rho);
}

Biweight biweight_for_efficiency(double efficiency) {
  if (!(efficiency >= 0.55 && efficiency <= 0.99)) {
    throw InputError(fmt::format("robust gmwm: efficiency {} is outside [0.55, 0.99] (0.55: the biweight's "
                                 "50 % breakdown point; 0.99: almost the classical estimate)",
                                 efficiency));
  }
  // e(c) increases with c: bisection on [1.5, 12].
  double lo = 1.5, hi = 12.0;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (biweight_scale_efficiency(mid) < efficiency ? lo : hi) = mid;
  }
  Biweight b;
  b.c = 0.5 * (lo + hi);
  const Moments m = moments(b.c);
  b.delta = m.delta;
  b.efficiency = m.z_drho * m.z_drho / (2.0 * m.var_rho);
  return b;
}

double biweight_scale2(std::span<const double> x, const Biweight& b) {
  if (x.empty()) throw InputError("robust scale: no values");
  // Start: the median absolute value / Phi^-1(3/4), the 50 %-breakdown scale.
  std::vector<double> a(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) a[i] = std::abs(x[i]);
  const auto mid = a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2);
  std::nth_element(a.begin(), mid, a.end());
  const double mad = *mid / 0.6744897501960817;
  if (!(mad > 0.0)) return 0.0;
  // g(s) = mean rho(x / s) - delta falls with s: bracket on log s, then Illinois regula falsi.
  auto g = [&](double log_s) {
    const double s = std::exp(log_s);
    double sum = 0.0;
    for (double v : x) sum += rho(v / s, b.c);
    return sum / static_cast<double>(x.size()) - b.delta;
  };
  double lo = std::log(mad) - 0.5, hi = std::log(mad) + 0.5;
  double glo = g(lo), ghi = g(hi);
  for (int i = 0; i < 60 && glo < 0.0; ++i) {
    hi = lo, ghi = glo;
    lo -= 1.0;
    glo = g(lo);
  }
  for (int i = 0; i < 60 && ghi > 0.0; ++i) {
    lo = hi, glo = ghi;
    hi += 1.0;
    ghi = g(hi);
  }
  int side = 0;
  for (int it = 0; it < 200 && hi - lo > 1e-13; ++it) {
    const double r = (lo * ghi - hi * glo) / (ghi - glo);
    const double gr = g(r);
    if (gr == 0.0) return std::exp(2.0 * r);
    if ((gr > 0.0) == (glo > 0.0)) {
      lo = r, glo = gr;
      if (side == -1) ghi *= 0.5;
      side = -1;
    } else {
      hi = r, ghi = gr;
      if (side == 1) glo *= 0.5;
      side = 1;
    }
  }
  const double s = std::exp(0.5 * (lo + hi));
  return s * s;
}

std::vector<double> robust_avar(std::span<const double> phase_si, double tau0_s,
                                std::span<const std::size_t> m, const Biweight& b) {
  std::vector<double> out;
  std::vector<double> w;
  for (std::size_t mi : m) {
    if (mi == 0 || 2 * mi >= phase_si.size()) {
      throw InputError(fmt::format("robust wavelet variance: averaging factor {} needs more than {} phase samples",
                                   mi, 2 * mi));
    }
    const std::size_t n = phase_si.size() - 2 * mi;
    const double scale = 1.0 / (2.0 * static_cast<double>(mi) * tau0_s);
    w.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
      w[t] = (phase_si[t + 2 * mi] - 2.0 * phase_si[t + mi] + phase_si[t]) * scale;
    }
    out.push_back(2.0 * biweight_scale2(w, b));
  }
  return out;
}

}  // namespace imunoise::fit
