// Text input speed: one column of a CSV "t,gx,gy" written with %.9e (the large-file case:
// 1e7 rows, 495 MB) read by read_text_file in three ways, side by side in one run:
//   line_by_line_1thread  the plain single-threaded line-by-line read (bulk_rows = false)
//   bulk_1thread          the bulk row parser on one thread
//   bulk_2threads         the bulk row parser on two threads (the row pool: 1 MiB chunks cut at
//                         line ends, parsed in place in the file's memory map)
// and, as the floor, fread_only: the plain single-threaded read of the same file into an 8 MiB
// buffer, no parsing.
// The file is written once to $TMPDIR (rows from IMUNOISE_BENCH_ROWS, default 1e7) and read
// from the page cache. Run by hand:
//   build/default/bench/bench_text_reader --benchmark_counters_tabular=true
// Counters: GB_per_s = file bytes / wall time; process_cpu_s = CPU time of all the process's
// threads per read (getrusage: user + system), since the CPU column counts the main thread only.
// Other sessions share this machine's 2 cores: note `uptime` beside every run.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

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

double process_cpu_s() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void set_rate(benchmark::State& state, double cpu_s) {
  state.counters["process_cpu_s"] = cpu_s / static_cast<double>(state.iterations());
  state.counters["GB_per_s"] = benchmark::Counter(
      static_cast<double>(std::filesystem::file_size(csv_file())) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate);
}

void BM_read(benchmark::State& state, bool bulk, unsigned threads) {
  imunoise::io::TextReadOptions options;
  options.column = std::string("gy");
  options.bulk_rows = bulk;
  options.threads = threads;
  const double cpu0 = process_cpu_s();
  for (auto _ : state) {
    const auto columns = imunoise::io::read_text_file(csv_file(), options);
    benchmark::DoNotOptimize(columns.values.data());
  }
  set_rate(state, process_cpu_s() - cpu0);
}

void BM_fread_only(benchmark::State& state) {
  std::vector<char> buffer(std::size_t{1} << 23);
  const double cpu0 = process_cpu_s();
  for (auto _ : state) {
    std::FILE* in = std::fopen(csv_file().c_str(), "rb");
    std::setvbuf(in, nullptr, _IONBF, 0);
    std::size_t total = 0;
    while (const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), in)) total += got;
    std::fclose(in);
    benchmark::DoNotOptimize(total);
  }
  set_rate(state, process_cpu_s() - cpu0);
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
