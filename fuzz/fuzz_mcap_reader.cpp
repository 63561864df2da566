// libFuzzer target for the MCAP reader: for any bytes the reader must either return a
// recording or throw InputError; anything else (a crash, a sanitizer report, another
// exception, a leak, a hang, memory beyond -rss_limit_mb) is a bug.
//
// Input layout: byte 0 chooses the topic asked for (so both the decoding path and the
// topic-listing refusal are explored), the rest is the file content. Seeds: fuzz/seeds_mcap/,
// small files written by the real writer (tests/io/).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static constexpr std::string_view topics[] = {"/imu", "/status", "/imu/data", ""};
  const std::string_view topic = topics[data[0] & 3u];
  try {
    const auto recording = imunoise::io::read_mcap_buffer(std::span(data + 1, size - 1), "fuzz", topic);
    (void)recording.sample_count();
  } catch (const imunoise::InputError&) {
  }
  return 0;
}
