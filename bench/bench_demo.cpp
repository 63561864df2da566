// Where the demo's time goes: `imunoise demo` is the README's first command and must finish
// in under 60 s on 2 cores. Each stage is timed alone (Google Benchmark, one iteration each:
// every stage takes seconds); the stage names say what is in them. Baseline in the same
// process: simulating the four gyros, the cost any study of them starts from.
//   build/default/bench/bench_demo --benchmark_min_time=1x
#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

#include "imunoise/study/demo.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"

namespace {

using namespace imunoise;

void BM_DemoSimulate(benchmark::State& state) {
  for (auto _ : state) {
    auto records = study::simulate_demo_records({});
    benchmark::DoNotOptimize(records.data());
  }
}

// Curves with confidence, fits, datasheet, navigation models, redundant fusion.
void BM_DemoStudy(benchmark::State& state) {
  const auto records = study::simulate_demo_records({});
  for (auto _ : state) {
    state.PauseTiming();
    auto copy = records;
    state.ResumeTiming();
    auto result = study::run_study(std::move(copy), study::demo_study_options());
    benchmark::DoNotOptimize(result.channels.data());
  }
}

// The document, the HTML/Markdown/CSV renderers and gnuplot's SVG and PNG figures.
void BM_DemoReport(benchmark::State& state) {
  const study::DemoOptions demo;
  const auto result = study::run_study(study::simulate_demo_records(demo), study::demo_study_options());
  const auto dir = std::filesystem::temp_directory_path() / ("imunoise-bench-demo-" + std::to_string(::getpid()));
  for (auto _ : state) {
    auto doc = study::study_json(result);
    doc["reference"] = study::demo_reference(result, demo);
    study::write_report(doc, dir.string(), {true, "", "gnuplot"});
  }
  std::filesystem::remove_all(dir);
}

}  // namespace

BENCHMARK(BM_DemoSimulate)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_DemoStudy)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_DemoReport)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();
