#pragma once
// Named sensor setups that regenerate a known situation.
//
// tg100: the paper's four TG-100 MEMS gyros at rest (paper.md, Table 2), 200 Hz, in deg/s:
//   gyro  Q (deg)   N (deg/sqrt(s))  B (deg/s)  K (deg/s/sqrt(s))
//   1     -         8.9e-4           5.9e-4     1.5e-5
//   2     -         8.8e-4           5.3e-4     1.1e-5
//   3     1.0e-7    8.8e-4           5.8e-4     0.9e-5
//   4     -         8.6e-4           5.3e-4     1.2e-5
// R negligible (no +1 slope in the paper's curves). Measurement range +-100 deg/s (Table 1),
// applied as saturation. Output in deg/s; the analog output (20 mV/(deg/s), Table 1) is
// obtained by setting each channel's OutputStage::scale_factor to kTg100VoltsPerDegPerSecond.
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/sim/generator.hpp"

namespace imunoise::sim {

inline constexpr double kTg100VoltsPerDegPerSecond = 0.020;

struct Preset {
  std::string name;
  std::string description;
  double rate_hz = 0.0;
  std::string unit;                   ///< rate unit of every parameter and of the output
  std::vector<ChannelSpec> channels;  ///< one per sensor, named
};

/// The presets this build knows, by name.
std::vector<std::string> preset_names();

/// The preset called `name`; throws InputError listing the known names otherwise.
Preset find_preset(std::string_view name);

}  // namespace imunoise::sim
