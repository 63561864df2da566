#pragma once
// Simulated redundant units: n gyros of the paper's TG-100 model (Table 2, deg/s) through the
// sensing axes of a geometry, under a body rate, in rad/s.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/load/record.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/sim/generator.hpp"

namespace imunoise::redundant_test {

inline constexpr double kDeg = std::numbers::pi / 180.0;
inline constexpr double kN = 8.9e-4;   // deg/sqrt(s)
inline constexpr double kB = 5.9e-4;   // deg/s
inline constexpr double kK = 1.5e-5;   // deg/s/sqrt(s)

inline sim::NoiseModel tg100(bool flicker_and_rrw = true) {
  sim::NoiseModel m;
  m.n_unit_sqrt_s = kN;
  if (flicker_and_rrw) {
    m.b_unit = kB;
    m.k_unit_per_sqrt_s = kK;
  }
  return m;
}

/// The true model of a simulated sensor, SI, as the analysis takes it.
inline redundant::SensorModel truth_model(const sim::NoiseModel& m) {
  redundant::SensorModel s;
  s.source = "truth";
  auto set = [](Coefficient& c, double v) {
    c.value = v * kDeg;
    c.identified = v > 0;
    c.ci_low = c.ci_high = c.value;
  };
  set(s.coefficients.random_walk, m.n_unit_sqrt_s);
  set(s.coefficients.bias_instability, m.b_unit);
  set(s.coefficients.rate_random_walk, m.k_unit_per_sqrt_s);
  return s;
}

/// Sensor records (rad/s): m_i = h_i . w(t) + noise_i, with the body rate w(t) (rad/s) averaged
/// over each sample as the simulator does (exact for a constant or linear-in-t rate; w is
/// evaluated at mid-sample).
/// One noise model per sensor (deg/s based, as the simulator's channels).
inline std::vector<std::vector<double>> simulate_unit(
    const redundant::Geometry& g, const std::vector<sim::NoiseModel>& models, double rate_hz, double duration_s,
    std::uint64_t seed, const std::function<std::array<double, 3>(double)>& body_rate_rad_s) {
  sim::SimulationSpec spec;
  spec.rate_hz = rate_hz;
  spec.duration_s = duration_s;
  spec.seed = seed;
  for (std::size_t i = 0; i < g.size(); ++i) spec.channels.push_back({models.at(i), {}, ""});
  sim::Generator gen(spec);
  const std::size_t n = gen.sample_count();
  std::vector<std::vector<double>> out(g.size(), std::vector<double>(n));
  std::vector<std::span<double>> spans;
  for (auto& o : out) spans.emplace_back(o);
  gen.generate_planar(spans, 2);
  for (std::size_t t = 0; t < n; ++t) {
    const auto w = body_rate_rad_s((static_cast<double>(t) + 0.5) / rate_hz);
    for (std::size_t i = 0; i < g.size(); ++i) {
      const auto& h = g.axes[i];
      out[i][t] = out[i][t] * kDeg + h[0] * w[0] + h[1] * w[1] + h[2] * w[2];
    }
  }
  return out;
}

/// The same noise model on every sensor.
inline std::vector<std::vector<double>> simulate_unit(
    const redundant::Geometry& g, const sim::NoiseModel& model, double rate_hz, double duration_s,
    std::uint64_t seed, const std::function<std::array<double, 3>(double)>& body_rate_rad_s) {
  return simulate_unit(g, std::vector<sim::NoiseModel>(g.size(), model), rate_hz, duration_s, seed, body_rate_rad_s);
}

inline std::vector<std::span<const double>> spans_of(const std::vector<std::vector<double>>& v) {
  std::vector<std::span<const double>> s;
  for (const auto& x : v) s.emplace_back(x);
  return s;
}

/// One record per simulated sensor ("sensor1", ...), rad/s, as the in-motion analysis takes them.
inline std::vector<Record> as_records(std::vector<std::vector<double>> rates, double rate_hz) {
  std::vector<Record> out;
  for (std::size_t i = 0; i < rates.size(); ++i) {
    out.push_back(rate_record("sensor" + std::to_string(i + 1), std::move(rates[i]), rate_hz,
                              Unit{"rad/s", Quantity::angular_rate, 1.0}));
  }
  return out;
}

}  // namespace imunoise::redundant_test
