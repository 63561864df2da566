// Simulator throughput, one core, per noise term and for the paper's 4-gyro preset.
// Run (Release): ./build/default/bench/bench_sim --benchmark_counters_tabular=true
// The "samples/s" counter is the figure quoted in docs/simulator.md; targets (issue): >= 5e7
// for white / random walk / Gauss-Markov, >= 1e7 for flicker, and 6 h x 200 Hz x 4 gyros in
// about a second.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "imunoise/sim/generator.hpp"
#include "imunoise/sim/presets.hpp"
#include "imunoise/sim/rng.hpp"

using namespace imunoise::sim;

namespace {

constexpr std::size_t kChunk = 65536;
constexpr double kRate = 200.0;
constexpr double kDuration = 21600.0;  // sets the default flicker range [5 ms, 6 h]: 15 poles

void run_channel(benchmark::State& state, const NoiseModel& model) {
  ChannelSpec spec;
  spec.noise = model;
  ChannelGenerator g(spec, kRate, kDuration, 1, 0);
  std::vector<double> out(kChunk);
  for (auto _ : state) {
    g.generate(out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["samples/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kChunk), benchmark::Counter::kIsRate);
}

void BM_Normals(benchmark::State& state) {
  NormalGenerator g(Xoshiro256StarStar(1));
  std::vector<double> out(kChunk);
  for (auto _ : state) {
    g.fill(out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["normals/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kChunk), benchmark::Counter::kIsRate);
}

void BM_Quantization(benchmark::State& s) { NoiseModel m; m.q_unit_s = 1e-7; run_channel(s, m); }
void BM_WhiteN(benchmark::State& s) { NoiseModel m; m.n_unit_sqrt_s = 8.9e-4; run_channel(s, m); }
void BM_RateRandomWalkK(benchmark::State& s) { NoiseModel m; m.k_unit_per_sqrt_s = 1.5e-5; run_channel(s, m); }
void BM_GaussMarkov(benchmark::State& s) {
  NoiseModel m;
  m.gm_sigma_unit = 1e-3;
  m.gm_time_s = 10.0;
  run_channel(s, m);
}
void BM_FlickerB(benchmark::State& s) { NoiseModel m; m.b_unit = 5.9e-4; run_channel(s, m); }
void BM_RateRampR(benchmark::State& s) { NoiseModel m; m.r_unit_per_s = 1e-6; run_channel(s, m); }
void BM_Sinusoid(benchmark::State& s) {
  NoiseModel m;
  m.sine_amplitude_unit = 1e-3;
  m.sine_frequency_hz = 1.0;
  run_channel(s, m);
}
void BM_Tg100Gyro1(benchmark::State& s) { run_channel(s, find_preset("tg100").channels[0].noise); }

// The whole preset: 6 h at 200 Hz, 4 gyros (17.28 million samples), in memory chunks.
void BM_Tg100Preset6h(benchmark::State& state) {
  const unsigned threads = static_cast<unsigned>(state.range(0));
  SimulationSpec spec;
  const Preset p = find_preset("tg100");
  spec.rate_hz = p.rate_hz;
  spec.duration_s = kDuration;
  spec.channels = p.channels;
  std::vector<double> chunk(4 * kChunk);
  for (auto _ : state) {
    Generator g(spec);
    while (g.generate_interleaved(chunk, threads) != 0) benchmark::DoNotOptimize(chunk.data());
  }
  state.counters["samples/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 4 * 4320000.0,
                                                   benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_Normals);
BENCHMARK(BM_Quantization);
BENCHMARK(BM_WhiteN);
BENCHMARK(BM_RateRandomWalkK);
BENCHMARK(BM_GaussMarkov);
BENCHMARK(BM_FlickerB);
BENCHMARK(BM_RateRampR);
BENCHMARK(BM_Sinusoid);
BENCHMARK(BM_Tg100Gyro1);
BENCHMARK(BM_Tg100Preset6h)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

BENCHMARK_MAIN();
