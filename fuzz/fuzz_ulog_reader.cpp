// libFuzzer target for the PX4 ULog reader: for any bytes the reader must either return a
// recording or throw InputError that says how to fix the input ("fix:"); anything else (a
// crash, a sanitizer report, another exception, a message without a fix, a leak, a hang,
// memory beyond -rss_limit_mb) is a bug.
//
// Input layout: byte 0 chooses the topic asked for (each IMU topic's layout and the
// topic-listing refusal are explored), the rest is the file content. Seeds: fuzz/seeds_ulog/,
// small logs written by tests/io/writers/write_ulog.py.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static constexpr std::string_view topics[] = {"sensor_combined", "vehicle_imu", "sensor_gyro", "sensor_accel",
                                                "vehicle_angular_velocity", "vehicle_acceleration", "vehicle_status", ""};
  const std::string_view topic = topics[data[0] & 7u];
  try {
    const auto recording = imunoise::io::read_ulog_buffer(std::span(data + 1, size - 1), "fuzz", topic);
    (void)recording.sample_count();
  } catch (const imunoise::InputError& e) {
    if (std::string_view(e.what()).find("fix:") == std::string_view::npos) __builtin_trap();
  }
  return 0;
}
