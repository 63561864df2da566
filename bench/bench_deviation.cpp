// Deviation engine throughput against a straightforward implementation of the same formulas
// (one independent pass over the data per factor, as NumPy or AllanTools do), both run here
// on the same in-memory phase array. Run by hand:
//   build/native/bench/bench_deviation --benchmark_counters_tabular=true
// Counters: ns_per_sample (wall time / phase samples), GB_per_s (8 bytes per phase sample
// per call / wall time), terms_per_ns (terms summed over all factors / wall time).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "imunoise/confidence/fill_confidence.hpp"
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
  } else if (e == Estimator::hdev) {  // non-overlapping: start indices step by m
    for (std::size_t k = 0; k + 3 * m < n; k += m) {
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

// The library's default path (deviation, then noise identification and confidence intervals
// at every tau) against the deviation alone (--no-ci), same data, same run.
void BM_default_path(benchmark::State& state, Estimator e, bool with_ci, unsigned threads) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto& x = phase_of_size(n);
  const auto f = factors_for(e, n, "octave");
  imunoise::ConfidenceOptions options;
  options.threads = threads;
  for (auto _ : state) {
    auto points = imunoise::compute_deviation(e, x, 0.005, f, {threads});
    if (with_ci) {
      auto info = imunoise::fill_confidence(points, e, x, options);
      benchmark::DoNotOptimize(info.data());
    }
    benchmark::DoNotOptimize(points.data());
  }
  set_counters(state, n, f, e);
}

}  // namespace

// Registers the engine on 1 and 2 threads and the naive baseline, for each size.
void register_case(const char* name, Estimator e, const char* grid,
                   std::initializer_list<std::int64_t> sizes) {
  const std::string base(name);
  for (const unsigned threads : {1u, 2u}) {
    auto* b = benchmark::RegisterBenchmark((base + "_" + std::to_string(threads) + "thread").c_str(),
                                           BM_engine, e, grid, threads);
    for (const auto n : sizes) b->Arg(n);
    b->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  auto* naive = benchmark::RegisterBenchmark((base + "_naive").c_str(), BM_naive, e, grid);
  for (const auto n : sizes) naive->Arg(n);
  naive->Unit(benchmark::kMillisecond)->UseRealTime();
}

int main(int argc, char** argv) {
  register_case("oadev_octave", Estimator::oadev, "octave", {1'000'000, 10'000'000});
  register_case("oadev_perdecade10", Estimator::oadev, "perdecade:10", {10'000'000});
  register_case("oadev_all", Estimator::oadev, "all", {100'000});
  register_case("ohdev_all", Estimator::ohdev, "all", {100'000});
  register_case("ohdev_octave", Estimator::ohdev, "octave", {1'000'000, 10'000'000});
  register_case("mdev_octave", Estimator::mdev, "octave", {1'000'000, 10'000'000});
  register_case("hdev_octave", Estimator::hdev, "octave", {1'000'000, 10'000'000});
  for (const Estimator e : {Estimator::oadev, Estimator::mdev}) {
    for (const bool with_ci : {false, true}) {
      const std::string name = std::string(imunoise::estimator_name(e)) + "_octave_2threads_" +
                               (with_ci ? "with_ci" : "no_ci");
      benchmark::RegisterBenchmark(name.c_str(), BM_default_path, e, with_ci, 2u)
          ->Arg(10'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();
    }
  }
  // Every factor of 1e6 samples: 2.5e11 second-difference terms (AllanTools: ~800 s), mostly
  // through the FFT correlations (src/core/correlation_sums.hpp).
  for (const Estimator e : {Estimator::oadev, Estimator::ohdev}) {
    const std::string name = std::string(imunoise::estimator_name(e)) + "_all_1e6_2threads";
    benchmark::RegisterBenchmark(name.c_str(), BM_engine, e, "all", 2u)
        ->Arg(1'000'000)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
