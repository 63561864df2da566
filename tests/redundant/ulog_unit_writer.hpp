#pragma once
// Writes a PX4 ULog file of a simulated multi-IMU unit, following the published format
// specification (https://docs.px4.io/main/en/dev_log/ulog_file_format.html: header, flag bits
// 'B', formats 'F', subscriptions 'A', data 'D'), independently of imunoise's reader (which is
// checked against the reference reader in tests/io). Each instance of sensor_gyro / sensor_accel
// (multi_id 0, 1, ...) holds x y z as float32 at its own timestamp_sample.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace imunoise::redundant_test {

struct UlogInstance {
  std::vector<std::uint64_t> timestamp_us;   ///< timestamp_sample of each message
  std::array<std::vector<double>, 3> xyz;    ///< values (rad/s or m/s^2), written as float32
};

class UlogWriter {
 public:
  UlogWriter() {
    const unsigned char magic[] = {'U', 'L', 'o', 'g', 0x01, 0x12, 0x35, 0x01};
    bytes_.insert(bytes_.end(), magic, magic + 8);
    put<std::uint64_t>(bytes_, 1'000'000);
    std::vector<unsigned char> flags(40, 0);  // compat, incompat, appended offsets: all 0
    message('B', flags);
    for (const char* name : {"sensor_gyro", "sensor_accel"}) {
      const std::string f = std::string(name) +
                            ":uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
                            "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;";
      message('F', std::vector<unsigned char>(f.begin(), f.end()));
    }
  }

  /// Subscribes `topic` instance `multi_id` and appends its messages (all of one instance, in
  /// time order; the reader groups by instance, so the interleaving does not matter to it).
  void add(const std::string& topic, std::uint8_t multi_id, const UlogInstance& inst) {
    const auto id = static_cast<std::uint16_t>(next_id_++);
    std::vector<unsigned char> a;
    put<std::uint8_t>(a, multi_id);
    put<std::uint16_t>(a, id);
    a.insert(a.end(), topic.begin(), topic.end());
    message('A', a);
    for (std::size_t q = 0; q < inst.timestamp_us.size(); ++q) {
      std::vector<unsigned char> d;
      put<std::uint16_t>(d, id);
      put<std::uint64_t>(d, inst.timestamp_us[q] + 150);  // published a little after the sample
      put<std::uint64_t>(d, inst.timestamp_us[q]);
      put<std::uint32_t>(d, 0x2100U + multi_id);
      for (std::size_t a = 0; a < 3; ++a) put<float>(d, static_cast<float>(inst.xyz[a][q]));
      put<float>(d, 45.0F);
      put<std::uint32_t>(d, 0);
      for (int c = 0; c < 3; ++c) put<std::uint8_t>(d, 0);
      put<std::uint8_t>(d, 1);
      message('D', d);
    }
  }

  void write(const std::string& path) const {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes_.data()), static_cast<std::streamsize>(bytes_.size()));
  }

 private:
  template <class T>
  static void put(std::vector<unsigned char>& b, T v) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));  // little-endian hosts, as the format is
    b.insert(b.end(), raw, raw + sizeof(T));
  }
  void message(char type, const std::vector<unsigned char>& body) {
    put<std::uint16_t>(bytes_, static_cast<std::uint16_t>(body.size()));
    put<std::uint8_t>(bytes_, static_cast<std::uint8_t>(type));
    bytes_.insert(bytes_.end(), body.begin(), body.end());
  }
  std::vector<unsigned char> bytes_;
  int next_id_ = 0;
};

}  // namespace imunoise::redundant_test
