#include "imunoise/sim/request.hpp"

#include <cmath>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/sim/presets.hpp"
#include "imunoise/units.hpp"

namespace imunoise::sim {
namespace {

// A preset fixes the noise model, the channels and the unit: a conflicting option fails.
void check_preset_conflicts(const SimulationRequest& r, const Preset& preset) {
  if (!r.noise_given.empty()) {
    throw InputError(fmt::format("{} cannot be combined with --preset {} (the preset fixes the noise model; "
                                 "drop one of them)", r.noise_given.front(), r.preset));
  }
  if (r.channels) {
    throw InputError(fmt::format("--channels cannot be combined with --preset {} (it has {} channels)", r.preset,
                                 preset.channels.size()));
  }
  if (r.unit && parse_unit(*r.unit).name != preset.unit) {
    throw InputError(fmt::format("the {} preset's coefficients are in {}; drop --units or give --units {}",
                                 r.preset, preset.unit, preset.unit));
  }
}

std::string rate_unit_name(const std::string& text) {
  const Unit unit = parse_unit(text);
  if (unit.quantity != Quantity::angular_rate && unit.quantity != Quantity::acceleration &&
      unit.quantity != Quantity::dimensionless) {
    throw InputError("--units " + text +
                     " is not a rate unit; give the unit of the sensor output, e.g. deg/s, rad/s, m/s^2, g");
  }
  return unit.name;
}

}  // namespace

SimulationPlan plan_simulation(const SimulationRequest& r) {
  SimulationPlan plan;
  SimulationSpec& spec = plan.spec;
  spec.duration_s = r.duration_s;
  spec.seed = r.seed;
  if (!r.preset.empty()) {
    const Preset preset = find_preset(r.preset);
    check_preset_conflicts(r, preset);
    plan.unit = preset.unit;
    spec.rate_hz = r.rate_hz.value_or(preset.rate_hz);
    spec.channels = preset.channels;
  } else {
    if (!r.rate_hz) throw InputError("--rate HZ is required (the sample rate), unless --preset is given");
    plan.unit = rate_unit_name(r.unit.value_or("deg/s"));
    spec.rate_hz = *r.rate_hz;
    const std::size_t channels = r.channels.value_or(1);
    if (channels == 0) throw InputError("--channels must be at least 1");
    ChannelSpec channel;
    channel.noise = r.noise;
    spec.channels.assign(channels, channel);
  }
  const bool analog = r.volts_per_unit != 0.0;
  for (ChannelSpec& c : spec.channels) {
    // A preset keeps its own measurement range unless one is given.
    if (r.range_unit) {
      c.output.range_unit = *r.range_unit;
    } else if (r.preset.empty()) {
      c.output.range_unit = std::numeric_limits<double>::infinity();
    }
    c.output.scale_factor = r.scale_factor * (analog ? r.volts_per_unit : 1.0);
    c.output.offset_output = r.offset_output;
    c.output.lsb_output = r.lsb_output;
  }
  if (r.volts_per_unit < 0.0 || !std::isfinite(r.volts_per_unit)) {  // 0 = not given
    throw InputError("--volts-per-unit must be positive (e.g. 0.02 for the TG-100's 20 mV/(deg/s))");
  }
  plan.output_unit = analog ? "V" : (r.scale_factor != 1.0 ? plan.unit + " (scaled)" : plan.unit);
  return plan;
}

}  // namespace imunoise::sim
