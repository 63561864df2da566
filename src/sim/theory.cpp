#include "imunoise/sim/theory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <boost/math/quadrature/gauss.hpp>
#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/sim/flicker.hpp"
#include "imunoise/sim/gauss_markov.hpp"

namespace imunoise::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFloorFactor = 2.0 * std::numbers::ln2 / std::numbers::pi;  // (2 ln 2 / pi)

FlickerBank bank_of(const NoiseModel& m) {
  if (!(m.flicker_tau_min_s > 0.0) || !(m.flicker_tau_max_s > 0.0)) {
    throw InputError(
        "the flicker (B) term's exact theory needs its tau range: set flicker_tau_min_s and "
        "flicker_tau_max_s, or take the model from the generator (resolve_flicker_range)");
  }
  return design_flicker_bank(m.b_unit, m.flicker_tau_min_s, m.flicker_tau_max_s);
}

void check_tau(double tau_s) {
  if (!std::isfinite(tau_s) || !(tau_s > 0.0)) {
    throw InputError(fmt::format("tau = {:.10g} s must be positive and finite", tau_s));
  }
}

double sine_allan_variance(const NoiseModel& m, double tau_s) {
  if (m.sine_amplitude_unit == 0.0) return 0.0;
  const double a = m.sine_amplitude_unit;
  const double u = kPi * m.sine_frequency_hz * tau_s;
  if (u == 0.0) return 0.0;
  const double s = std::sin(u);
  const double ratio = s * s / u;
  return a * a * ratio * ratio;
}

// PSD without the band-limited Q term.
double psd_without_q(const NoiseModel& m, const FlickerBank* bank, double f_hz) {
  const double w = 2.0 * kPi * f_hz;
  double s = m.n_unit_sqrt_s * m.n_unit_sqrt_s;
  if (m.k_unit_per_sqrt_s > 0.0) s += m.k_unit_per_sqrt_s * m.k_unit_per_sqrt_s / (w * w);
  if (m.gm_sigma_unit > 0.0) s += gauss_markov_psd(m.gm_sigma_unit, m.gm_time_s, f_hz);
  if (m.b_unit > 0.0) {
    s += bank ? flicker_bank_psd(*bank, f_hz) : m.b_unit * m.b_unit / w;
  }
  return s;
}

double psd_q(const NoiseModel& m, double tau0_s, double f_hz) {
  if (m.q_unit_s == 0.0 || f_hz > 0.5 / tau0_s) return 0.0;
  const double w = 2.0 * kPi * f_hz;
  return w * w * tau0_s * m.q_unit_s * m.q_unit_s;
}

using Gauss = boost::math::quadrature::gauss<double, 20>;

// int_a^b S(x / (pi tau)) sin^4(x) / x^2 dx
template <class Psd>
double kernel_integral(const Psd& psd_of_f, double tau_s, double a, double b) {
  return Gauss::integrate(
      [&](double x) {
        const double s = std::sin(x);
        const double s2 = s * s;
        return psd_of_f(x / (kPi * tau_s)) * (s2 * s2) / (x * x);
      },
      a, b);
}

// (4 / (pi tau)) int_0^upper S sin^4 x / x^2 dx, upper finite or infinite, as described in
// theory.hpp. `upper` finite is used for the band-limited Q term (no tail).
template <class Psd>
double eq4_integral(const Psd& psd_of_f, double tau_s, double upper) {
  constexpr int kPeriods = 256;
  constexpr int kOctaves = 110;
  double sum = 0.0;
  // Octaves of (0, min(pi, upper)].
  const double first = std::min(kPi, upper);
  double hi = first;
  for (int j = 0; j < kOctaves; ++j) {
    const double lo = hi * 0.5;
    sum += kernel_integral(psd_of_f, tau_s, lo, hi);
    hi = lo;
  }
  // Whole periods of sin^4 (period pi).
  const double x_end = std::isfinite(upper) ? upper : kPi * kPeriods;
  for (double a = kPi; a < x_end; a += kPi) {
    const double b = std::min(a + kPi, x_end);
    sum += kernel_integral(psd_of_f, tau_s, a, b);
  }
  if (std::isfinite(upper)) return 4.0 / (kPi * tau_s) * sum;
  // Tail [X, inf): sin^4 x = 3/8 - cos(2x)/2 + cos(4x)/8. Smooth part by octaves of
  // g(x) = S(x / (pi tau)) / x^2; oscillating parts by integration by parts:
  // int_X^inf g cos(w x) dx = -g(X) sin(wX)/w - g'(X) cos(wX)/w^2 + O(g''/w^3).
  const double big_x = x_end;
  auto g = [&](double x) { return psd_of_f(x / (kPi * tau_s)) / (x * x); };
  double smooth = 0.0;
  double lo = big_x;
  for (int j = 0; j < kOctaves; ++j) {
    smooth += Gauss::integrate(g, lo, 2.0 * lo);
    lo *= 2.0;
  }
  const double h = 1e-3 * big_x;
  const double gx = g(big_x);
  const double dg = (g(big_x + h) - g(big_x - h)) / (2.0 * h);
  auto oscillating = [&](double w) {
    return -gx * std::sin(w * big_x) / w - dg * std::cos(w * big_x) / (w * w);
  };
  sum += 0.375 * smooth - 0.5 * oscillating(2.0) + 0.125 * oscillating(4.0);
  return 4.0 / (kPi * tau_s) * sum;
}

}  // namespace

AllanTerms allan_variance_terms(const NoiseModel& m, double tau_s, FlickerForm flicker) {
  check_tau(tau_s);
  AllanTerms t;
  t.q = 3.0 * m.q_unit_s * m.q_unit_s / (tau_s * tau_s);
  t.n = m.n_unit_sqrt_s * m.n_unit_sqrt_s / tau_s;
  if (m.b_unit > 0.0) {
    t.b = flicker == FlickerForm::bank ? flicker_bank_allan_variance(bank_of(m), tau_s)
                                       : kFloorFactor * m.b_unit * m.b_unit;
  }
  t.k = m.k_unit_per_sqrt_s * m.k_unit_per_sqrt_s * tau_s / 3.0;
  t.r = m.r_unit_per_s * m.r_unit_per_s * tau_s * tau_s / 2.0;
  if (m.gm_sigma_unit > 0.0) t.gm = gauss_markov_allan_variance(m.gm_sigma_unit, m.gm_time_s, tau_s);
  t.sine = sine_allan_variance(m, tau_s);
  return t;
}

double allan_variance(const NoiseModel& model, double tau_s, FlickerForm flicker) {
  return allan_variance_terms(model, tau_s, flicker).total();
}

double psd(const NoiseModel& m, double tau0_s, double f_hz, FlickerForm flicker) {
  FlickerBank bank;
  const bool use_bank = m.b_unit > 0.0 && flicker == FlickerForm::bank;
  if (use_bank) bank = bank_of(m);
  return psd_without_q(m, use_bank ? &bank : nullptr, f_hz) + psd_q(m, tau0_s, f_hz);
}

double allan_variance_eq4(const NoiseModel& m, double tau0_s, double tau_s, FlickerForm flicker) {
  check_tau(tau_s);
  check_tau(tau0_s);
  if (m.r_unit_per_s != 0.0) {
    throw InputError(
        "eq. 4 does not exist for a rate ramp (its PSD R^2/(2 pi f)^3 is not integrable at f = 0); "
        "use the closed form allan_variance");
  }
  FlickerBank bank;
  const bool use_bank = m.b_unit > 0.0 && flicker == FlickerForm::bank;
  if (use_bank) bank = bank_of(m);
  const FlickerBank* bank_ptr = use_bank ? &bank : nullptr;
  double total = 0.0;
  const bool has_continuous = m.n_unit_sqrt_s > 0.0 || m.k_unit_per_sqrt_s > 0.0 ||
                              m.gm_sigma_unit > 0.0 || m.b_unit > 0.0;
  if (has_continuous) {
    total += eq4_integral([&](double f) { return psd_without_q(m, bank_ptr, f); }, tau_s,
                          std::numeric_limits<double>::infinity());
  }
  if (m.q_unit_s > 0.0) {
    const double x_nyquist = kPi * tau_s * 0.5 / tau0_s;
    total += eq4_integral([&](double f) { return psd_q(m, tau0_s, f); }, tau_s, x_nyquist);
  }
  if (m.sine_amplitude_unit > 0.0 && m.sine_frequency_hz > 0.0) {
    // Line of power A^2/4 at +-f0: eq. 4 takes the f0 > 0 half, 4 (A^2/4) sin^4(u) / u^2.
    const double u = kPi * m.sine_frequency_hz * tau_s;
    const double s = std::sin(u);
    total += m.sine_amplitude_unit * m.sine_amplitude_unit * (s * s) * (s * s) / (u * u);
  }
  return total;
}

}  // namespace imunoise::sim
