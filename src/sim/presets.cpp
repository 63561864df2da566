#include "imunoise/sim/presets.hpp"

#include "imunoise/error.hpp"

namespace imunoise::sim {
namespace {

ChannelSpec tg100_gyro(const char* name, double q, double n, double b, double k) {
  ChannelSpec c;
  c.name = name;
  c.noise.q_unit_s = q;
  c.noise.n_unit_sqrt_s = n;
  c.noise.b_unit = b;
  c.noise.k_unit_per_sqrt_s = k;
  c.output.range_unit = 100.0;
  return c;
}

Preset tg100() {
  Preset p;
  p.name = "tg100";
  p.description =
      "four TG-100 MEMS gyros at rest, noise coefficients of the paper's Table 2, 200 Hz, deg/s, "
      "range +-100 deg/s";
  p.rate_hz = 200.0;
  p.unit = "deg/s";
  p.channels = {
      tg100_gyro("gyro1", 0.0, 8.9e-4, 5.9e-4, 0.15e-4),
      tg100_gyro("gyro2", 0.0, 8.8e-4, 5.3e-4, 0.11e-4),
      tg100_gyro("gyro3", 0.001e-4, 8.8e-4, 5.8e-4, 0.09e-4),
      tg100_gyro("gyro4", 0.0, 8.6e-4, 5.3e-4, 0.12e-4),
  };
  return p;
}

}  // namespace

std::vector<std::string> preset_names() { return {"tg100"}; }

Preset find_preset(std::string_view name) {
  if (name == "tg100") return tg100();
  std::string known;
  for (const auto& n : preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown preset '" + std::string(name) + "'; known presets: " + known);
}

}  // namespace imunoise::sim
