// Redundant-unit fusion throughput: four 6 h, 200 Hz gyro recordings (tetra) fused into body
// rates and parity with fault detection, in memory (after reading: the part `analyze` adds).
// Baseline in the same process: one pass that only sums the four inputs (the memory-bandwidth
// floor of reading them), and the same fusion without detection.
// Run (Release): ./build/default/bench/bench_redundant --benchmark_counters_tabular=true
// The "sensor_samples/s" counter is the figure quoted in docs/performance.md (target:
// >= 5e7 on 2 cores with detection).
#include <benchmark/benchmark.h>

#include <numeric>
#include <vector>

#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/sim/generator.hpp"

using namespace imunoise;
using namespace imunoise::redundant;

namespace {

constexpr double kRate = 200.0;
constexpr double kDuration = 21600.0;

struct Unit4 {
  Geometry geometry = make_geometry("tetra");
  std::vector<std::vector<double>> records;
  std::vector<SensorModel> models;
  Unit4() {
    sim::SimulationSpec spec;
    spec.rate_hz = kRate;
    spec.duration_s = kDuration;
    sim::NoiseModel m;
    m.n_unit_sqrt_s = 8.9e-4 * 0.0174533;
    m.b_unit = 5.9e-4 * 0.0174533;
    m.k_unit_per_sqrt_s = 1.5e-5 * 0.0174533;
    for (int i = 0; i < 4; ++i) spec.channels.push_back({m, {}, ""});
    sim::Generator g(spec);
    records.assign(4, std::vector<double>(g.sample_count()));
    std::vector<std::span<double>> s;
    for (auto& r : records) s.emplace_back(r);
    g.generate_planar(s, 2);
    SensorModel model;
    model.coefficients.random_walk.value = m.n_unit_sqrt_s;
    model.coefficients.bias_instability.value = m.b_unit;
    model.coefficients.rate_random_walk.value = m.k_unit_per_sqrt_s;
    models.assign(4, model);
  }
  std::vector<std::span<const double>> spans() const {
    std::vector<std::span<const double>> s;
    for (const auto& r : records) s.emplace_back(r);
    return s;
  }
};

const Unit4& unit() {
  static const Unit4 u;
  return u;
}

void count(benchmark::State& state) {
  const double per = static_cast<double>(unit().records.size() * unit().records[0].size());
  state.counters["sensor_samples/s"] =
      benchmark::Counter(per * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_BaselineSumInputs(benchmark::State& state) {
  for (auto _ : state) {
    double s = 0;
    for (const auto& r : unit().records) s += std::accumulate(r.begin(), r.end(), 0.0);
    benchmark::DoNotOptimize(s);
  }
  count(state);
}

void BM_Fuse(benchmark::State& state) {
  const Analysis a = analyze_unit(unit().geometry, unit().models);
  FusionOptions o;
  o.threads = static_cast<unsigned>(state.range(0));
  o.detect = state.range(1) != 0;
  for (auto _ : state) {
    auto f = fuse_records(a, unit().spans(), kRate, o);
    benchmark::DoNotOptimize(f.axes_rad_s[0].data());
  }
  count(state);
}

// The kernel alone: outputs allocated once (fuse_into), as a caller streaming or reusing
// buffers sees it.
void BM_FuseInto(benchmark::State& state) {
  const Analysis a = analyze_unit(unit().geometry, unit().models);
  FusionOptions o;
  o.threads = static_cast<unsigned>(state.range(0));
  o.detect = state.range(1) != 0;
  const std::size_t len = unit().records[0].size();
  std::vector<std::vector<double>> out(3 + a.parity.rows, std::vector<double>(len, 0.0));
  std::vector<std::span<double>> axes, parity;
  for (std::size_t r = 0; r < 3; ++r) axes.emplace_back(out[r]);
  for (std::size_t r = 3; r < out.size(); ++r) parity.emplace_back(out[r]);
  for (auto _ : state) {
    auto d = fuse_into(a, unit().spans(), kRate, o, axes, parity);
    benchmark::DoNotOptimize(out[0].data());
    benchmark::DoNotOptimize(d);
  }
  count(state);
}

}  // namespace

BENCHMARK(BM_FuseInto)->ArgsProduct({{1, 2}, {0, 1}})->ArgNames({"threads", "detect"})
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BaselineSumInputs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fuse)->ArgsProduct({{1, 2}, {0, 1}})->ArgNames({"threads", "detect"})
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
