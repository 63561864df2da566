// Navigation error: covariance propagation of a 6 h flight at 1 s steps, and 1000 Monte-Carlo
// runs of 1 h (target: < 5 s on 2 cores). Baselines in the same process: the
// step-by-step covariance propagation (the doubling's reference) and the simulator alone
// producing the Monte Carlo's gyro samples (its floor).
// Run (Release): ./build/default/bench/bench_nav --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <numbers>
#include <vector>

#include "imunoise/nav/navigation.hpp"
#include "imunoise/sim/generator.hpp"

using namespace imunoise;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Coefficient present(double v) {
  Coefficient c;
  c.value = v;
  c.identified = true;
  return c;
}

// The paper's gyro 1 (Table 2) on every axis.
nav::NavOptions tg100(double hours) {
  nav::NavOptions o;
  o.duration_s = hours * 3600.0;
  o.latitude_rad = 58.5 * kDeg;
  for (auto& a : o.axes) {
    a.coefficients.random_walk = present(8.9e-4 * kDeg);
    a.coefficients.bias_instability = present(5.9e-4 * kDeg);
    a.coefficients.rate_random_walk = present(0.15e-4 * kDeg);
  }
  return o;
}

void BM_Covariance6h(benchmark::State& state) {
  nav::NavOptions o = tg100(6.0);
  o.models = {nav::Model::covariance};
  o.step_s = static_cast<double>(state.range(0));
  o.covariance_per_step = state.range(1) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(nav::navigation_error(o));
  state.SetLabel(std::string(o.covariance_per_step ? "step by step" : "doubling") + ", report every " +
                 std::to_string(state.range(0)) + " s");
}
BENCHMARK(BM_Covariance6h)->Args({60, 0})->Args({60, 1})->Args({1, 0})->Unit(benchmark::kMillisecond);

void BM_MonteCarlo1000x1h(benchmark::State& state) {
  nav::NavOptions o = tg100(1.0);
  o.models = {nav::Model::montecarlo};
  o.runs = 1000;
  o.threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(nav::navigation_error(o));
  state.SetLabel(std::to_string(state.range(0)) + " thread(s)");
}
BENCHMARK(BM_MonteCarlo1000x1h)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

// Floor: the simulator alone, the same 1000 x 3 x 3600 samples, one thread.
void BM_SimulatorSamplesOf1000x1h(benchmark::State& state) {
  sim::ChannelSpec spec;
  spec.noise.n_unit_sqrt_s = 8.9e-4 * kDeg;
  spec.noise.b_unit = 5.9e-4 * kDeg;
  spec.noise.k_unit_per_sqrt_s = 0.15e-4 * kDeg;
  spec.noise.flicker_tau_min_s = 1.0;
  spec.noise.flicker_tau_max_s = 3600.0;
  std::vector<double> out(3600);
  for (auto _ : state) {
    for (int run = 0; run < 1000; ++run) {
      for (int axis = 0; axis < 3; ++axis) {
        sim::ChannelGenerator g(spec, 1.0, 3600.0, static_cast<std::uint64_t>(run), static_cast<std::uint64_t>(axis));
        g.generate(out);
        benchmark::DoNotOptimize(out.data());
      }
    }
  }
}
BENCHMARK(BM_SimulatorSamplesOf1000x1h)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
