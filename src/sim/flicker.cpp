#include "deterministic_fp.hpp"  // first: no fused multiply-add in this file

#include "imunoise/sim/flicker.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/sim/gauss_markov.hpp"
#include "imunoise/sim/portable_math.hpp"

namespace imunoise::sim {

FlickerBank design_flicker_bank(double b_unit, double tau_min_s, double tau_max_s) {
  if (!std::isfinite(b_unit) || b_unit < 0.0) {
    throw InputError(fmt::format("bias instability B = {:.10g} must be finite and >= 0", b_unit));
  }
  if (!std::isfinite(tau_min_s) || !std::isfinite(tau_max_s) || !(tau_min_s > 0.0) ||
      !(tau_max_s > tau_min_s)) {
    throw InputError(fmt::format("flicker tau range [{:.10g}, {:.10g}] s is invalid: need 0 < tau_min < tau_max, both finite",
                                 tau_min_s, tau_max_s));
  }
  const double decades = std::log10(tau_max_s / tau_min_s);
  if (decades > kFlickerMaxDecades) {
    throw InputError(fmt::format(
        "flicker tau range [{:.10g}, {:.10g}] s spans {:.10g} decades; the generator honours at most {:.10g} "
        "(narrow the flicker tau range)",
        tau_min_s, tau_max_s, std::round(decades * 10.0) / 10.0, kFlickerMaxDecades));
  }
  FlickerBank bank;
  bank.tau_min_s = tau_min_s;
  bank.tau_max_s = tau_max_s;
  if (b_unit == 0.0) return bank;

  // Portable functions only: the pole parameters decide simulated bits.
  const double ln10 = portable::log(10.0);
  const double ln_r = ln10 / kFlickerPolesPerDecade;
  const double r = portable::exp(ln_r);
  const double t_lo = tau_min_s / kFlickerLowMargin;
  const double span = portable::log(tau_max_s * kFlickerHighMargin / t_lo) / ln_r;
  const int count = static_cast<int>(std::ceil(span - 1e-9)) + 1;
  const double variance = b_unit * b_unit * ln_r / std::numbers::pi;
  bank.poles.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double t = t_lo * portable::exp(ln_r * static_cast<double>(i));
    const double v = (i == count - 1) ? variance * r / (r - 1.0) : variance;
    bank.poles.push_back({std::sqrt(v), t});
  }
  bank.white_n_unit_sqrt_s = std::sqrt(2.0 * variance * t_lo / (r - 1.0));
  return bank;
}

double flicker_bank_allan_variance(const FlickerBank& bank, double tau_s) {
  double sum = bank.white_n_unit_sqrt_s * bank.white_n_unit_sqrt_s / tau_s;
  for (const auto& pole : bank.poles) {
    sum += gauss_markov_allan_variance(pole.sigma_unit, pole.time_s, tau_s);
  }
  return sum;
}

double flicker_bank_psd(const FlickerBank& bank, double f_hz) {
  double sum = bank.white_n_unit_sqrt_s * bank.white_n_unit_sqrt_s;
  for (const auto& pole : bank.poles) sum += gauss_markov_psd(pole.sigma_unit, pole.time_s, f_hz);
  return sum;
}

}  // namespace imunoise::sim
