#include "imunoise/sim/noise_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/sim/flicker.hpp"

namespace imunoise::sim {
namespace {

// Numbers in messages read as a user would type them: up to 10 significant digits ({:.10g}).

void require_finite(double value, const char* name) {
  if (!std::isfinite(value)) {
    throw InputError(fmt::format("{} = {:.10g} is not a finite number", name, value));
  }
}

void require_non_negative(double value, const char* name, const char* what) {
  require_finite(value, name);
  if (value < 0.0) {
    throw InputError(
        fmt::format("{} = {:.10g} is negative; {} is an intensity: give its magnitude (>= 0)", name, value, what));
  }
}

std::string empty_flicker_range(double tau_min_s, double tau_max_s) {
  return fmt::format("flicker tau range [{:.10g}, {:.10g}] s is empty: flicker-tau-max must exceed flicker-tau-min",
                     tau_min_s, tau_max_s);
}

}  // namespace

void validate(const NoiseModel& m) {
  require_non_negative(m.q_unit_s, "Q", "angle (quantization) noise");
  require_non_negative(m.n_unit_sqrt_s, "N", "angle random walk");
  require_non_negative(m.b_unit, "B", "bias instability");
  require_non_negative(m.k_unit_per_sqrt_s, "K", "rate random walk");
  require_finite(m.r_unit_per_s, "R");
  require_non_negative(m.gm_sigma_unit, "gm-sigma", "the Gauss-Markov standard deviation");
  require_non_negative(m.gm_time_s, "gm-tau", "the Gauss-Markov correlation time");
  require_non_negative(m.sine_amplitude_unit, "sine-amp", "the sinusoid amplitude");
  require_non_negative(m.sine_frequency_hz, "sine-freq", "the sinusoid frequency");
  require_finite(m.sine_phase_rad, "sine-phase");
  require_finite(m.bias_unit, "bias");
  require_non_negative(m.flicker_tau_min_s, "flicker-tau-min", "a time");
  require_non_negative(m.flicker_tau_max_s, "flicker-tau-max", "a time");
  if (m.gm_sigma_unit > 0.0 && !(m.gm_time_s > 0.0)) {
    throw InputError(fmt::format("gm-sigma = {:.10g} needs a positive Gauss-Markov correlation time (gm-tau, seconds)",
                                 m.gm_sigma_unit));
  }
  if (m.flicker_tau_min_s > 0.0 && m.flicker_tau_max_s > 0.0 &&
      !(m.flicker_tau_max_s > m.flicker_tau_min_s)) {
    throw InputError(empty_flicker_range(m.flicker_tau_min_s, m.flicker_tau_max_s));
  }
}

void validate(const OutputStage& o) {
  if (std::isnan(o.range_unit) || !(o.range_unit > 0.0)) {
    throw InputError(fmt::format("range = {:.10g} must be positive (the measurement range, +-range in the rate unit)",
                                 o.range_unit));
  }
  require_finite(o.scale_factor, "scale factor");
  if (o.scale_factor == 0.0) {
    throw InputError("scale factor must not be zero (output units per rate unit, e.g. 0.02 V per deg/s)");
  }
  require_finite(o.offset_output, "output offset");
  require_non_negative(o.lsb_output, "lsb", "the ADC step");
}

void check_sampling(const NoiseModel& m, double rate_hz, double duration_s) {
  if (!std::isfinite(rate_hz) || !(rate_hz > 0.0)) {
    throw InputError(fmt::format("rate = {:.10g} Hz must be positive and finite", rate_hz));
  }
  if (!std::isfinite(duration_s) || !(duration_s > 0.0)) {
    throw InputError(fmt::format("duration = {:.10g} s must be positive and finite", duration_s));
  }
  if (duration_s * rate_hz < 1.0 - 1e-9) {  // tolerance: n / rate * rate may round below n
    throw InputError(fmt::format("duration {:.10g} s is shorter than one sample at {:.10g} Hz (need duration >= 1/rate)",
                                 duration_s, rate_hz));
  }
  if (duration_s * rate_hz > 9.0e15) {
    throw InputError(fmt::format("duration {:.10g} s at {:.10g} Hz exceeds 9e15 samples", duration_s, rate_hz));
  }
  if (m.sine_amplitude_unit > 0.0 && rate_hz < 2.0 * m.sine_frequency_hz) {
    throw InputError(fmt::format(
        "rate {:.10g} Hz is below twice the sinusoid frequency {:.10g} Hz: sample at >= {:.10g} Hz or lower sine-freq",
        rate_hz, m.sine_frequency_hz, 2.0 * m.sine_frequency_hz));
  }
  if (m.b_unit > 0.0) {
    const NoiseModel r = resolve_flicker_range(m, rate_hz, duration_s);
    const double tau0 = 1.0 / rate_hz;
    if (r.flicker_tau_min_s < tau0 * (1.0 - 1e-12)) {
      throw InputError(fmt::format(
          "flicker-tau-min = {:.10g} s is below the sample interval {:.10g} s: no Allan deviation exists there; "
          "use >= 1/rate",
          r.flicker_tau_min_s, tau0));
    }
    if (!(r.flicker_tau_max_s > r.flicker_tau_min_s)) {
        throw InputError(empty_flicker_range(r.flicker_tau_min_s, r.flicker_tau_max_s));
    }
    design_flicker_bank(m.b_unit, r.flicker_tau_min_s, r.flicker_tau_max_s);  // throws if too wide
  }
}

NoiseModel resolve_flicker_range(NoiseModel model, double rate_hz, double duration_s) {
  if (model.flicker_tau_min_s == 0.0) model.flicker_tau_min_s = 1.0 / rate_hz;
  if (model.flicker_tau_max_s == 0.0) {
    model.flicker_tau_max_s = std::max(duration_s, 10.0 * model.flicker_tau_min_s);
  }
  return model;
}

bool is_silent(const NoiseModel& m) {
  return m.q_unit_s == 0.0 && m.n_unit_sqrt_s == 0.0 && m.b_unit == 0.0 &&
         m.k_unit_per_sqrt_s == 0.0 && m.r_unit_per_s == 0.0 && m.gm_sigma_unit == 0.0 &&
         m.sine_amplitude_unit == 0.0 && m.bias_unit == 0.0;
}

}  // namespace imunoise::sim
