#include "imunoise/redundant/unit_simulation.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "imunoise/error.hpp"
#include "imunoise/sim/generator.hpp"

namespace imunoise::redundant {

std::array<double, 3> MotionProfile::mean_rate(double t0_s, double duration_s) const {
  std::array<double, 3> w = constant_rad_s;
  for (const auto& line : lines) {
    // Mean of sin over the sample: sin(mid) sin(pi f T) / (pi f T), stable for small f T.
    const double x = std::numbers::pi * line.frequency_hz * duration_s;
    const double sinc = x == 0.0 ? 1.0 : std::sin(x) / x;
    for (std::size_t a = 0; a < 3; ++a) {
      const double mid = 2 * std::numbers::pi * line.frequency_hz * (t0_s + 0.5 * duration_s) + line.phase_rad[a];
      w[a] += line.amplitude_rad_s[a] * std::sin(mid) * sinc;
    }
  }
  return w;
}

MotionProfile tumble_profile(double amplitude_rad_s) {
  MotionProfile p;
  const double f[3] = {0.5, 0.31, 0.17};
  for (std::size_t a = 0; a < 3; ++a) {
    RotationLine line;
    line.frequency_hz = f[a];
    line.amplitude_rad_s[a] = amplitude_rad_s;
    line.phase_rad[a] = static_cast<double>(a);
    p.lines.push_back(line);
  }
  return p;
}

std::vector<std::vector<double>> simulate_unit(const Geometry& geometry, std::span<const UnitSensor> sensors,
                                               const MotionProfile& motion, double rate_hz, double duration_s,
                                               std::uint64_t seed) {
  const std::size_t n = geometry.size();
  if (sensors.size() != n) {
    throw InputError(fmt::format("simulate_unit: {} sensor specifications for the {} axes of geometry {}",
                                 sensors.size(), n, geometry.name));
  }
  for (const auto& line : motion.lines) {
    if (!(line.frequency_hz >= 0.0) || line.frequency_hz > rate_hz / 2) {
      throw InputError(fmt::format("simulate_unit: a rotation line at {} Hz is outside 0 .. {} Hz (the Nyquist "
                                   "frequency of {} Hz)", line.frequency_hz, rate_hz / 2, rate_hz));
    }
  }
  sim::SimulationSpec spec;
  spec.rate_hz = rate_hz;
  spec.duration_s = duration_s;
  spec.seed = seed;
  bool motion_noise = false;
  for (std::size_t i = 0; i < n; ++i) {
    spec.channels.push_back({sensors[i].noise, {}, fmt::format("sensor{}", i + 1)});
    motion_noise = motion_noise || sensors[i].motion_noise_sqrt_s != 0.0;
  }
  sim::Generator gen(spec);
  const auto len = static_cast<std::size_t>(gen.sample_count());
  std::vector<std::vector<double>> out(n, std::vector<double>(len));
  {
    std::vector<std::span<double>> spans;
    for (auto& o : out) spans.emplace_back(o);
    gen.generate_planar(spans, 1);
  }
  std::vector<std::vector<double>> unit_white;
  if (motion_noise) {
    // Its own streams (another seed), so the sensors' noise is the same with or without it.
    sim::SimulationSpec white = spec;
    white.seed = seed ^ 0x5DEECE66DULL;
    for (auto& c : white.channels) {
      c.noise = sim::NoiseModel{};
      c.noise.n_unit_sqrt_s = 1.0;
    }
    sim::Generator wgen(white);
    unit_white.assign(n, std::vector<double>(len));
    std::vector<std::span<double>> spans;
    for (auto& o : unit_white) spans.emplace_back(o);
    wgen.generate_planar(spans, 1);
  }
  // Effective axes: (1 + s) (h + d_perp).
  std::vector<Axis> eff(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& h = geometry.axes[i];
    const auto& d = sensors[i].misalignment_rad;
    const double along = d[0] * h[0] + d[1] * h[1] + d[2] * h[2];
    const double s = 1.0 + 1e-6 * sensors[i].scale_factor_ppm;
    for (std::size_t a = 0; a < 3; ++a) eff[i][a] = s * (h[a] + d[a] - along * h[a]);
  }
  const double tau0 = 1.0 / rate_hz;
  for (std::size_t t = 0; t < len; ++t) {
    const auto w = motion.mean_rate(static_cast<double>(t) * tau0, tau0);
    for (std::size_t i = 0; i < n; ++i) {
      out[i][t] += eff[i][0] * w[0] + eff[i][1] * w[1] + eff[i][2] * w[2];
      if (motion_noise) {
        const auto& h = geometry.axes[i];
        const double sensed = std::abs(h[0] * w[0] + h[1] * w[1] + h[2] * w[2]);
        out[i][t] += sensors[i].motion_noise_sqrt_s * sensed * unit_white[i][t];
      }
    }
  }
  return out;
}

}  // namespace imunoise::redundant
