#include "imunoise/sim/noise_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "imunoise/error.hpp"
#include "imunoise/sim/flicker.hpp"
#include "message.hpp"

namespace imunoise::sim {
namespace {

using detail::num;

void require_finite(double value, const char* name) {
  if (!std::isfinite(value)) {
    throw InputError(std::string(name) + " = " + num(value) + " is not a finite number");
  }
}

void require_non_negative(double value, const char* name, const char* what) {
  require_finite(value, name);
  if (value < 0.0) {
    throw InputError(std::string(name) + " = " + num(value) + " is negative; " + what +
                     " is an intensity: give its magnitude (>= 0)");
  }
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
    throw InputError("gm-sigma = " + num(m.gm_sigma_unit) +
                     " needs a positive Gauss-Markov correlation time (gm-tau, seconds)");
  }
  if (m.flicker_tau_min_s > 0.0 && m.flicker_tau_max_s > 0.0 &&
      !(m.flicker_tau_max_s > m.flicker_tau_min_s)) {
    throw InputError("flicker tau range [" + num(m.flicker_tau_min_s) + ", " +
                     num(m.flicker_tau_max_s) + "] s is empty: flicker-tau-max must exceed flicker-tau-min");
  }
}

void validate(const OutputStage& o) {
  if (std::isnan(o.range_unit) || !(o.range_unit > 0.0)) {
    throw InputError("range = " + num(o.range_unit) +
                     " must be positive (the measurement range, +-range in the rate unit)");
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
    throw InputError("rate = " + num(rate_hz) + " Hz must be positive and finite");
  }
  if (!std::isfinite(duration_s) || !(duration_s > 0.0)) {
    throw InputError("duration = " + num(duration_s) + " s must be positive and finite");
  }
  if (duration_s * rate_hz < 1.0 - 1e-9) {  // tolerance: n / rate * rate may round below n
    throw InputError("duration " + num(duration_s) + " s is shorter than one sample at " +
                     num(rate_hz) + " Hz (need duration >= 1/rate)");
  }
  if (duration_s * rate_hz > 9.0e15) {
    throw InputError("duration " + num(duration_s) + " s at " + num(rate_hz) +
                     " Hz exceeds 9e15 samples");
  }
  if (m.sine_amplitude_unit > 0.0 && rate_hz < 2.0 * m.sine_frequency_hz) {
    throw InputError("rate " + num(rate_hz) + " Hz is below twice the sinusoid frequency " +
                     num(m.sine_frequency_hz) + " Hz: sample at >= " +
                     num(2.0 * m.sine_frequency_hz) + " Hz or lower sine-freq");
  }
  if (m.b_unit > 0.0) {
    const NoiseModel r = resolve_flicker_range(m, rate_hz, duration_s);
    const double tau0 = 1.0 / rate_hz;
    if (r.flicker_tau_min_s < tau0 * (1.0 - 1e-12)) {
      throw InputError("flicker-tau-min = " + num(r.flicker_tau_min_s) +
                       " s is below the sample interval " + num(tau0) +
                       " s: no Allan deviation exists there; use >= 1/rate");
    }
    if (!(r.flicker_tau_max_s > r.flicker_tau_min_s)) {
      throw InputError("flicker tau range [" + num(r.flicker_tau_min_s) + ", " +
                       num(r.flicker_tau_max_s) + "] s is empty: flicker-tau-max must exceed flicker-tau-min");
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
