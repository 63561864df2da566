// Deviation engine throughput against a straightforward implementation of the same formulas
// (one independent pass over the data per factor, as NumPy or AllanTools do), both run here
// on the same in-memory phase array. Run by hand:
//   build/native/bench/bench_deviation --benchmark_counters_tabular=true
// Counters: ns_per_sample (wall time / phase samples), GB_per_s (8 bytes per phase sample
// per call / wall time), terms_per_ns (terms summed over all factors / wall time).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/tau_grid.hpp"

namespace {

using imunoise::Estimator;

const std::vector<double>& phase_of_size(std::size_t n) {
  static std::vector<double> cached;
  if (cached.size() != n) {
    std::mt19937_64 engine(42);
    std::vector<double> rate(n - 1);
    for (auto& v : rate) v = static_cast<double>(engine() >> 11) * 0x1.0p-53 - 0.5;
    cached = imunoise::phase_from_rate(rate, 0.005, 0.0);
  }
  return cached;
}

std::vector<std::size_t> factors_for(Estimator e, std::size_t n, const char* grid) {
  return imunoise::averaging_factors(imunoise::parse_tau_grid(grid), 200.0,
                                     imunoise::max_averaging_factor(e, n));
}

// The baseline: for each factor, one loop over all start indices, terms summed in order.
double naive_sum(Estimator e, const std::vector<double>& x, std::size_t m) {
  double s = 0.0;
  const std::size_t n = x.size();
  if (e == Estimator::oadev) {
    for (std::size_t k = 0; k + 2 * m < n; ++k) {
      const double d = x[k + 2 * m] - 2 * x[k + m] + x[k];
      s += d * d;
    }
  } else if (e == Estimator::ohdev) {
    for (std::size_t k = 0; k + 3 * m < n; ++k) {
      const double d = x[k + 3 * m] - 3 * x[k + 2 * m] + 3 * x[k + m] - x[k];
      s += d * d;
    }
  } else {  // mdev, AllanTools' running-sum formulation
    double v = 0.0;
    for (std::size_t i = 0; i < m; ++i) v += x[i + 2 * m] - 2 * x[i + m] + x[i];
    for (std::size_t j = 0; j + 3 * m <= n; ++j) {
      s += v * v;
      if (j + 3 * m < n) v += x[j + 3 * m] - 3 * x[j + 2 * m] + 3 * x[j + m] - x[j];
    }
  }
  return s;
}

void set_counters(benchmark::State& state, std::size_t n, const std::vector<std::size_t>& f,
                  Estimator e) {
  double terms = 0;
  for (auto m : f) terms += static_cast<double>(imunoise::term_count(e, n, m));
  state.counters["taus"] = static_cast<double>(f.size());
  state.counters["ns_per_sample"] = benchmark::Counter(
      static_cast<double>(n) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["GB_per_s"] = benchmark::Counter(static_cast<double>(n) * 8e-9,
                                                  benchmark::Counter::kIsIterationInvariantRate);
  state.counters["terms_per_ns"] = benchmark::Counter(terms * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_engine(benchmark::State& state, Estimator e, const char* grid, unsigned threads) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto& x = phase_of_size(n);
  const auto f = factors_for(e, n, grid);
  for (auto _ : state) {
    auto points = imunoise::compute_deviation(e, x, 0.005, f, {threads});
    benchmark::DoNotOptimize(points.data());
  }
  set_counters(state, n, f, e);
}

void BM_naive(benchmark::State& state, Estimator e, const char* grid) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto& x = phase_of_size(n);
  const auto f = factors_for(e, n, grid);
  for (auto _ : state) {
    double total = 0;
    for (auto m : f) total += naive_sum(e, x, m);
    benchmark::DoNotOptimize(total);
  }
  set_counters(state, n, f, e);
}

}  // namespace

#define IMUNOISE_BENCH(name, ...) \
  BENCHMARK_CAPTURE(BM_engine, name##_1thread, __VA_ARGS__, 1)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_engine, name##_2threads, __VA_ARGS__, 2)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_naive, name##_naive, __VA_ARGS__)->Unit(benchmark::kMillisecond)->UseRealTime()

IMUNOISE_BENCH(oadev_octave, Estimator::oadev, "octave")->Arg(1'000'000)->Arg(10'000'000);
IMUNOISE_BENCH(oadev_perdecade10, Estimator::oadev, "perdecade:10")->Arg(10'000'000);
IMUNOISE_BENCH(oadev_all, Estimator::oadev, "all")->Arg(100'000);
IMUNOISE_BENCH(ohdev_octave, Estimator::ohdev, "octave")->Arg(1'000'000)->Arg(10'000'000);
IMUNOISE_BENCH(mdev_octave, Estimator::mdev, "octave")->Arg(1'000'000)->Arg(10'000'000);
BENCHMARK_CAPTURE(BM_engine, hdev_octave_1thread, Estimator::hdev, "octave", 1)
    ->Arg(1'000'000)->Arg(10'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();
// oadev over every factor on 1e6 samples: 2.5e11 terms (AllanTools: ~800 s). Opt-in:
// --benchmark_filter=all_1e6
BENCHMARK_CAPTURE(BM_engine, oadev_all_1e6_2threads, Estimator::oadev, "all", 2)
    ->Arg(1'000'000)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

BENCHMARK_MAIN();
