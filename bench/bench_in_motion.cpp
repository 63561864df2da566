// In-motion noise (the N-cornered hat in parity space) through the whole analysis: four 6 h,
// 200 Hz gyro recordings of the tetrahedral unit under the 200 deg/s tumble (the target:
// under 10 s on 2 cores), from the records in memory: the parity, the leakage regression on the
// fused motion, the Allan covariance matrices at every octave tau, the GLS solve and the unit's
// checks (study::analyze_in_motion). Variants: with the timing regression (a container's
// instances), and the six-gyro dodecahedral unit, whose every sensor also gets its curve and fit.
// The simulation of the records is outside the timing (done once).
// Run (Release): ./build/default/bench/bench_in_motion --benchmark_counters_tabular=true
// The "sensor_samples/s" counter and the wall time are the figures for docs/redundant.md; record
// them only on a quiet machine (uptime load < 1.5).
#include <benchmark/benchmark.h>

#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "imunoise/fit/fit.hpp"
#include "imunoise/load/record.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/redundant/unit_simulation.hpp"
#include "imunoise/study/in_motion.hpp"

using namespace imunoise;

namespace {

constexpr double kRate = 200.0;
constexpr double kDuration = 21600.0;
constexpr double kDeg = std::numbers::pi / 180.0;

// The paper's TG-100 noise on every sensor (N, B, K), independent streams.
const std::vector<std::vector<double>>& unit_records(const std::string& geometry) {
  static std::map<std::string, std::vector<std::vector<double>>> cache;
  auto& r = cache[geometry];
  if (r.empty()) {
    const auto g = redundant::make_geometry(geometry);
    std::vector<redundant::UnitSensor> sensors(g.size());
    for (auto& s : sensors) {
      s.noise.n_unit_sqrt_s = 8.9e-4 * kDeg;
      s.noise.b_unit = 5.9e-4 * kDeg;
      s.noise.k_unit_per_sqrt_s = 1.5e-5 * kDeg;
    }
    r = redundant::simulate_unit(g, sensors, redundant::tumble_profile(200.0 * kDeg), kRate, kDuration, 11);
  }
  return r;
}

std::vector<Record> records_of(const std::vector<std::vector<double>>& rates) {
  std::vector<Record> out;
  for (std::size_t i = 0; i < rates.size(); ++i) {
    out.push_back(rate_record("gyro" + std::to_string(i + 1), rates[i], kRate,
                              Unit{"rad/s", Quantity::angular_rate, 1.0}));
  }
  return out;
}

void run(benchmark::State& state, const std::string& geometry, bool timing) {
  const auto g = redundant::make_geometry(geometry);
  const auto& rates = unit_records(geometry);
  redundant::InMotionOptions o;
  o.remove_timing_leakage = timing;
  std::size_t taus = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto recs = records_of(rates);  // the copy is the loader's output, not the analysis
    state.ResumeTiming();
    const auto unit = study::analyze_in_motion(g, std::move(recs), o, fit::FitOptions{});
    taus = unit.result.points.size();
    benchmark::DoNotOptimize(unit.result.common.data());
  }
  const double samples = static_cast<double>(rates.size() * rates[0].size());
  state.counters["sensor_samples/s"] = benchmark::Counter(samples, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["sensors"] = static_cast<double>(rates.size());
  state.counters["taus"] = static_cast<double>(taus);
}

void BM_InMotionTetra6h(benchmark::State& state) { run(state, "tetra", false); }
void BM_InMotionTetra6hTiming(benchmark::State& state) { run(state, "tetra", true); }
void BM_InMotionDodeca6hPerSensorFits(benchmark::State& state) { run(state, "dodeca", false); }

}  // namespace

BENCHMARK(BM_InMotionTetra6h)->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_InMotionTetra6hTiming)->Unit(benchmark::kSecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_InMotionDodeca6hPerSensorFits)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK_MAIN();
