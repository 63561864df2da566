// libFuzzer target for the ROS 2 SQLite bag reader: for any bytes written as a .db3 file the
// reader must either return a recording or throw InputError; anything else (a crash, a
// sanitizer report, another exception, a leak, a hang, memory beyond -rss_limit_mb) is a bug.
// The reader takes a path (SQLite opens files), so each input goes through a temporary file of
// this process. Byte 0 chooses the topic (the IMU topic, another one, a missing one). Seeds:
// fuzz/seeds_db3/, one-file bags written by tests/io/writers/write_db3.py.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("imunoise-fuzz-" + std::to_string(::getpid()) + ".db3")).string();
  static constexpr std::string_view topics[] = {"/imu", "/status", "/none", ""};
  const std::string_view topic = topics[data[0] & 3u];
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    const auto recording = imunoise::io::read_ros2_db3(path, topic);
    (void)recording.sample_count();
  } catch (const imunoise::InputError&) {
  }
  std::filesystem::remove(path);
  return 0;
}
