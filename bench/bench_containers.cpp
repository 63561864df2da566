// Reading IMU recordings from containers: a ROS 1 bag and an MCAP file (bench_containers.sh), or
// a ROS 2 SQLite bag and a PX4 ULog (bench_ros2_ulog.sh), of a 6 h, 200 Hz record
// (4.32 M sensor_msgs Imu messages) against the target of < 3 s each, with the
// in-process baseline of reading the same file's bytes (read(2) into one buffer: what the page
// cache and memory bandwidth allow). Files are written by the real writers
// (bench/bench_containers.sh makes them once, then runs this):
//   build/default/bench/bench_containers FILE TOPIC [FILE TOPIC ...] [--benchmark_* flags]
// Counters: messages, MB/s of file, target_ms, process_cpu_s (CPU time of all the process's
// threads per read, user + system: the CPU column counts the main thread only).
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "imunoise/io/recording.hpp"

namespace {

double process_cpu_s() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void read_bytes(benchmark::State& state, std::string path) {
  const auto size = std::filesystem::file_size(path);
  std::vector<char> buffer(size);
  const double cpu0 = process_cpu_s();
  for (auto _ : state) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    std::size_t done = 0;
    while (done < size) {
      const auto got = ::read(fd, buffer.data() + done, size - done);
      if (got <= 0) break;
      done += static_cast<std::size_t>(got);
    }
    ::close(fd);
    benchmark::DoNotOptimize(buffer.data());
  }
  state.counters["MB_per_s"] = benchmark::Counter(static_cast<double>(size) / 1e6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
  state.counters["process_cpu_s"] = (process_cpu_s() - cpu0) / static_cast<double>(state.iterations());
}

void read_recording(benchmark::State& state, std::string path, std::string topic) {
  const auto size = std::filesystem::file_size(path);
  std::size_t messages = 0;
  const double cpu0 = process_cpu_s();
  for (auto _ : state) {
    imunoise::io::RecordingOptions options;
    options.topic = topic;
    const auto recording = imunoise::io::read_recording(path, options);
    messages = recording.sample_count();
    benchmark::DoNotOptimize(recording.channels.data());
  }
  state.counters["messages"] = static_cast<double>(messages);
  state.counters["MB_per_s"] = benchmark::Counter(static_cast<double>(size) / 1e6,
                                                  benchmark::Counter::kIsIterationInvariantRate);
  state.counters["process_cpu_s"] = (process_cpu_s() - cpu0) / static_cast<double>(state.iterations());
  state.counters["target_ms"] = 3000;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> rest = {argv[0]};
  std::vector<std::pair<std::string, std::string>> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) == 0) {
      rest.push_back(argv[i]);
    } else if (i + 1 < argc) {
      files.emplace_back(a, argv[i + 1]);
      ++i;
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s FILE TOPIC [FILE TOPIC ...] [--benchmark_* flags]\n", argv[0]);
    return 2;
  }
  for (const auto& [path, topic] : files) {
    const std::string name = std::filesystem::path(path).filename().string();
    benchmark::RegisterBenchmark(("baseline_read_bytes/" + name).c_str(), read_bytes, path)
        ->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("read_recording/" + name).c_str(), read_recording, path, topic)
        ->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  int count = static_cast<int>(rest.size());
  benchmark::Initialize(&count, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
