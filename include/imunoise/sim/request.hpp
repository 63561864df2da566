#pragma once
// What a user asks the simulator for (a noise model or a preset, the output stage, the unit),
// turned into the SimulationSpec the generator runs. The checks that need the whole request
// (a preset fixes the noise model, the channel count and the unit) live here, not in the CLI.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/sim/generator.hpp"

namespace imunoise::sim {

struct SimulationRequest {
  std::optional<double> rate_hz;          ///< sample rate (Hz); required without a preset
  double duration_s = 21600.0;            ///< record length (s)
  std::uint64_t seed = 1;
  NoiseModel noise;                       ///< every channel's model (without a preset), in `unit`
  std::vector<std::string> noise_given;   ///< names of the noise parameters the user set ("--N", ...)
  std::optional<double> range_unit;       ///< saturate at +-range (unit); a preset keeps its own
  double scale_factor = 1.0;              ///< multiplies the output
  double volts_per_unit = 0.0;            ///< analog output in V per unit (0: not given)
  double offset_output = 0.0;             ///< added after scaling (output unit)
  double lsb_output = 0.0;                ///< ADC step (output unit; 0: none)
  std::optional<std::string> unit;        ///< rate unit of the parameters (default deg/s)
  std::string preset;                     ///< "" or a preset name (presets.hpp)
  std::optional<std::size_t> channels;    ///< independent channels (default 1)
};

struct SimulationPlan {
  SimulationSpec spec;
  std::string unit;         ///< unit of the parameters and of the rate ("deg/s")
  std::string output_unit;  ///< unit of the written samples: "V", "<unit> (scaled)" or the unit
};

/// The spec of a request. InputError naming the option and the fix for a noise parameter,
/// --channels or another --units given with a preset, a missing rate, a unit that is not a
/// rate, zero channels, or a negative or non-finite volts per unit.
SimulationPlan plan_simulation(const SimulationRequest& request);

}  // namespace imunoise::sim
