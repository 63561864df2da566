// The cost of the mergeable accumulators (imunoise/difference_accumulator.hpp) that `dev --mpi`
// and `fit --mpi` run on each rank: accumulating a slice, and one node of the merge tree
// (decode the partner's image, merge, encode) against the slice size L. Baseline in the same
// process: the one-pass oadev of the same samples (BM_OnePass). Run by hand:
//   build/default/bench/bench_merge --benchmark_counters_tabular=true
// Factors: octave, up to L/4 (each slice is a quarter of the record in the model), so the
// edges hold W = 2 m_max = L/2 samples: the worst case, where an edge is as long as it can be.
// Counters: ns_per_sample (wall / L), image_MB (bytes one merge sends), ns_per_edge_sample.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "imunoise/deviation.hpp"
#include "imunoise/difference_accumulator.hpp"
#include "imunoise/phase.hpp"

namespace {

using imunoise::DifferenceAccumulator;
using imunoise::Estimator;

std::vector<double> phase_of_size(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::vector<double> rate(n - 1);
  for (auto& v : rate) v = static_cast<double>(engine() >> 11) * 0x1.0p-53 - 0.5;
  return imunoise::phase_from_rate(rate, 0.005, 0.0);
}

std::vector<std::size_t> octave_factors(std::size_t max_m) {
  std::vector<std::size_t> f;
  for (std::size_t m = 1; m <= max_m; m *= 2) f.push_back(m);
  return f;
}

void BM_OnePass(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto x = phase_of_size(n, 1);
  const auto factors = octave_factors(n / 4);
  for (auto _ : state) {
    benchmark::DoNotOptimize(imunoise::compute_deviation(Estimator::oadev, x, 0.005, factors, {1}));
  }
  state.counters["ns_per_sample"] = benchmark::Counter(
      static_cast<double>(n) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_PushSlice(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto x = phase_of_size(n, 1);
  const auto factors = octave_factors(n / 4);
  for (auto _ : state) {
    DifferenceAccumulator acc(Estimator::oadev, factors);
    acc.push(x);
    benchmark::DoNotOptimize(acc.size());
  }
  state.counters["ns_per_sample"] = benchmark::Counter(
      static_cast<double>(n) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// One tree node: receive the right neighbour's image, merge it into ours, send the result on.
void BM_MergeNode(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto factors = octave_factors(n / 4);
  DifferenceAccumulator left(Estimator::oadev, factors, 0), right(Estimator::oadev, factors, n - 1);
  left.push(phase_of_size(n, 1));
  right.push(phase_of_size(n, 2));
  const auto left_image = left.to_bytes();
  const auto right_image = right.to_bytes();
  for (auto _ : state) {
    auto merged = DifferenceAccumulator::from_bytes(left_image);
    merged.merge(DifferenceAccumulator::from_bytes(right_image));
    benchmark::DoNotOptimize(merged.to_bytes());
  }
  state.counters["image_MB"] = static_cast<double>(right_image.size()) / 1e6;
  state.counters["ns_per_edge_sample"] = benchmark::Counter(
      static_cast<double>(left.window()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_OnePass)->RangeMultiplier(8)->Range(1 << 12, 1 << 21)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PushSlice)->RangeMultiplier(8)->Range(1 << 12, 1 << 21)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MergeNode)->RangeMultiplier(8)->Range(1 << 12, 1 << 21)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
