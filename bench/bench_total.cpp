// The total, Theo1 and time-error estimators against their speed targets, and against the
// literal definitions kept in the tests (tests/core/reference_total.hpp) as an in-process naive
// baseline. Run by hand (Release):
//   build/default/bench/bench_total --benchmark_counters_tabular=true
// Targets (octave taus, all threads): at 4,000 samples 100x faster than AllanTools' 31 s
// (mtotdev) and 4 s (theo1), i.e. < 310 ms and < 40 ms; mtotdev, htotdev, theo1 on 1e5 samples
// < 1 s each; mtie on 1e6 samples < 1 s. Counter target_ms states the target.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/reference_total.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"

namespace {

using imunoise::Estimator;

// White rate noise with a large offset, integrated (as the CLI does for rate input).
std::vector<double> make_phase(std::size_t n) {
  std::mt19937_64 engine(42);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> rate(n - 1);
  for (auto& v : rate) v = 100.0 + g(engine);
  return imunoise::phase_from_rate(rate, 0.005, imunoise::compensated_mean(rate));
}

const std::vector<double>& phase_of_size(std::size_t n) {
  static std::vector<double> cached;
  if (cached.size() != n) cached = make_phase(n);
  return cached;
}

std::vector<std::size_t> octave(Estimator e, std::size_t n) {
  return imunoise::estimator_averaging_factors(e, imunoise::parse_tau_grid("octave"), 200.0, n);
}

void fast(benchmark::State& state, Estimator e, double target_ms) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto& x = phase_of_size(n);
  const auto factors = octave(e, n);
  for (auto _ : state) {
    auto points = imunoise::compute_deviation(e, x, 0.005, factors);
    benchmark::DoNotOptimize(points.data());
  }
  state.counters["taus"] = static_cast<double>(factors.size());
  state.counters["target_ms"] = target_ms;
}

double naive_one(Estimator e, const std::vector<double>& x, std::size_t m) {
  switch (e) {
    case Estimator::totdev: return imunoise::test::reference_totdev(x, 0.005, m);
    case Estimator::mtotdev: return imunoise::test::reference_mtotdev(x, 0.005, m);
    case Estimator::htotdev: return imunoise::test::reference_htotdev(x, 0.005, m);
    case Estimator::theo1: return imunoise::test::reference_theo1(x, 0.005, m);
    case Estimator::mtie: return imunoise::test::reference_mtie(x, m);
    default: return imunoise::test::reference_tierms(x, m);
  }
}

void naive(benchmark::State& state, Estimator e) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto& x = phase_of_size(n);
  const auto factors = octave(e, n);
  for (auto _ : state) {
    double s = 0.0;
    for (const std::size_t m : factors) {
      if (e == Estimator::htotdev && m == 1) continue;
      s += naive_one(e, x, m);
    }
    benchmark::DoNotOptimize(s);
  }
  state.counters["taus"] = static_cast<double>(factors.size());
}

// 4,000 samples: the size of the AllanTools comparison (31 s mtotdev, ~4 s theo1).
BENCHMARK_CAPTURE(fast, totdev_4k, Estimator::totdev, 0)->Arg(4000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fast, mtotdev_4k, Estimator::mtotdev, 310)->Arg(4000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fast, htotdev_4k, Estimator::htotdev, 0)->Arg(4000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fast, theo1_4k, Estimator::theo1, 40)->Arg(4000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fast, mtie_4k, Estimator::mtie, 0)->Arg(4000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(naive, totdev_4k, Estimator::totdev)->Arg(4000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(naive, theo1_4k, Estimator::theo1)->Arg(4000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(naive, mtie_4k, Estimator::mtie)->Arg(4000)->Unit(benchmark::kMillisecond)->Iterations(1);
// The literal mtot/htot definitions are O(N m^2) per tau: 1,000 samples keep them to seconds.
BENCHMARK_CAPTURE(fast, mtotdev_1k, Estimator::mtotdev, 0)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(naive, mtotdev_1k, Estimator::mtotdev)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(naive, htotdev_1k, Estimator::htotdev)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(1);
// 1e5 samples: the long-record targets.
BENCHMARK_CAPTURE(fast, totdev_1e5, Estimator::totdev, 1000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fast, mtotdev_1e5, Estimator::mtotdev, 1000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(fast, htotdev_1e5, Estimator::htotdev, 1000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(fast, theo1_1e5, Estimator::theo1, 1000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(fast, tierms_1e6, Estimator::tierms, 1000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fast, mtie_1e6, Estimator::mtie, 1000)->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
