// Text input speed: one column of a CSV "t,gx,gy" written with %.9e (the case of issue 18:
// 1e7 rows, 495 MB) read by read_text_file in three ways, side by side in one run:
//   line_by_line_1thread  the plain single-threaded line-by-line read (bulk_rows = false)
//   bulk_1thread          the bulk row parser on one thread
//   bulk_2threads         the bulk row parser on two threads (byte ranges split at line ends)
// and, as the floor, fread_only: the same file read into an 8 MiB buffer (the reader's block),
// no parsing.
// The file is written once to $TMPDIR (rows from IMUNOISE_BENCH_ROWS, default 1e7) and read
// from the page cache. Run by hand:
//   build/default/bench/bench_text_reader --benchmark_counters_tabular=true
// Counter GB_per_s: file bytes / wall time.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "imunoise/io/text_reader.hpp"

namespace {

std::size_t row_count() {
  const char* text = std::getenv("IMUNOISE_BENCH_ROWS");
  return text != nullptr ? static_cast<std::size_t>(std::atof(text)) : 10'000'000;
}

const std::filesystem::path& csv_file() {
  static const std::filesystem::path path = [] {
    const std::size_t rows = row_count();
    const char* tmp = std::getenv("TMPDIR");
    const std::filesystem::path file =
        std::filesystem::path(tmp != nullptr ? tmp : "/tmp") /
        ("imunoise_bench_text_" + std::to_string(rows) + ".csv");
    if (!std::filesystem::exists(file)) {
      const std::string partial = file.string() + ".part";
      std::FILE* out = std::fopen(partial.c_str(), "wb");
      if (out == nullptr) std::abort();
      std::mt19937_64 engine(5);
      std::normal_distribution<double> gaussian(0.0, 1e-3);
      std::fputs("t,gx,gy\n", out);
      for (std::size_t i = 0; i < rows; ++i) {
        std::fprintf(out, "%.9e,%.9e,%.9e\n", static_cast<double>(i) * 0.005, gaussian(engine),
                     gaussian(engine));
      }
      std::fclose(out);
      std::filesystem::rename(partial, file);
    }
    return file;
  }();
  return path;
}

void set_rate(benchmark::State& state) {
  state.counters["GB_per_s"] = benchmark::Counter(
      static_cast<double>(std::filesystem::file_size(csv_file())) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate);
}

void BM_read(benchmark::State& state, bool bulk, unsigned threads) {
  imunoise::io::TextReadOptions options;
  options.column = std::string("gy");
  options.bulk_rows = bulk;
  options.threads = threads;
  for (auto _ : state) {
    const auto columns = imunoise::io::read_text_file(csv_file(), options);
    benchmark::DoNotOptimize(columns.values.data());
  }
  set_rate(state);
}

void BM_fread_only(benchmark::State& state) {
  std::vector<char> buffer(std::size_t{1} << 23);
  for (auto _ : state) {
    std::FILE* in = std::fopen(csv_file().c_str(), "rb");
    std::setvbuf(in, nullptr, _IONBF, 0);
    std::size_t total = 0;
    while (const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), in)) total += got;
    std::fclose(in);
    benchmark::DoNotOptimize(total);
  }
  set_rate(state);
}

}  // namespace

int main(int argc, char** argv) {
  csv_file();  // written before any timing
  benchmark::RegisterBenchmark("fread_only", BM_fread_only)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("line_by_line_1thread", BM_read, false, 1u)
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("bulk_1thread", BM_read, true, 1u)
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("bulk_2threads", BM_read, true, 2u)
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
