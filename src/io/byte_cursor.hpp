#pragma once
// Internal to src/io: bounds-checked little-endian reading of container files, and a read-only
// memory map. Every read past the end throws InputError naming the file and the byte offset,
// which is how truncated and corrupt bag/MCAP files become messages instead of crashes.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/io/recording.hpp"
#include "mapped_file.hpp"

namespace imunoise::io::detail {

class ByteCursor {
 public:
  /// `where` names the file (and, for decompressed chunks, the chunk) in messages; `base` is
  /// the file offset of bytes[0] when the bytes are part of the file (else 0 and `where` says).
  ByteCursor(std::span<const unsigned char> bytes, std::string where, std::uint64_t base = 0)
      : bytes_(bytes), where_(std::move(where)), base_(base) {}

  [[nodiscard]] std::size_t pos() const { return pos_; }
  [[nodiscard]] std::size_t size() const { return bytes_.size(); }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }
  [[nodiscard]] bool at_end() const { return pos_ == bytes_.size(); }
  void seek(std::size_t pos, std::string_view what) {
    if (pos > bytes_.size()) fail(std::string(what) + " points past the end of the data");
    pos_ = pos;
  }

  std::uint8_t u8(std::string_view what) { return take(1, what)[0]; }
  std::uint16_t u16(std::string_view what) { return le<std::uint16_t>(what); }
  std::uint32_t u32(std::string_view what) { return le<std::uint32_t>(what); }
  std::uint64_t u64(std::string_view what) { return le<std::uint64_t>(what); }
  std::span<const unsigned char> take(std::uint64_t n, std::string_view what) {
    if (n > remaining()) {
      fail(std::string(what) + " needs " + std::to_string(n) + " bytes but only " +
           std::to_string(remaining()) + " remain (truncated or corrupt)");
    }
    auto out = bytes_.subspan(pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return out;
  }
  std::string_view text(std::uint64_t n, std::string_view what) {
    auto b = take(n, what);
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(where_ + ": byte " + std::to_string(base_ + pos_) + ": " + what +
                     "; fix: the file is corrupt or was cut short: copy it again, or repair it (rosbag reindex, mcap recover)");
  }
  [[nodiscard]] const std::string& where() const { return where_; }
  [[nodiscard]] std::uint64_t base() const { return base_; }

 private:
  template <class T>
  T le(std::string_view what) {
    auto b = take(sizeof(T), what);
    T v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(T{b[i]} << (8 * i));
    return v;
  }

  std::span<const unsigned char> bytes_;
  std::string where_;
  std::uint64_t base_ = 0;
  std::size_t pos_ = 0;
};

/// An owned byte buffer left uninitialised (decompression overwrites all of it: zero-filling
/// 1.5 GB first would cost a pass over memory).
class Bytes {
 public:
  Bytes() = default;
  explicit Bytes(std::size_t n) : data_(n ? new unsigned char[n] : nullptr), size_(n), capacity_(n) {}
  [[nodiscard]] unsigned char* data() { return data_.get(); }
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] std::span<const unsigned char> span() const { return {data_.get(), size_}; }
  /// Size n, contents undefined; the storage is kept when it is large enough.
  void resize_uninitialized(std::size_t n) {
    if (n > capacity_) {
      data_.reset();
      data_.reset(new unsigned char[n]);
      capacity_ = n;
    }
    size_ = n;
  }

 private:
  std::unique_ptr<unsigned char[]> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

/// Decompression buffers handed back and forth between the threads that decode chunks: a
/// fresh buffer per chunk would have the kernel map and zero new pages for every chunk (a
/// quarter of the CPU time of a zstd MCAP read before they were reused).
class BufferPool {
 public:
  Bytes take() {
    std::lock_guard lock(mutex_);
    if (free_.empty()) return {};
    Bytes out = std::move(free_.back());
    free_.pop_back();
    return out;
  }
  void give(Bytes&& bytes) {
    std::lock_guard lock(mutex_);
    free_.push_back(std::move(bytes));
  }

 private:
  std::mutex mutex_;
  std::vector<Bytes> free_;
};

/// Decompressors into `out` (resized to `expected`, the uncompressed size the container
/// states, which the output must match exactly). Throw InputError prefixed with `where`.
void decompress_bz2(std::span<const unsigned char> in, std::uint64_t expected, const std::string& where, Bytes& out);
void decompress_lz4_frame(std::span<const unsigned char> in, std::uint64_t expected, const std::string& where, Bytes& out);
void decompress_zstd(std::span<const unsigned char> in, std::uint64_t expected, const std::string& where, Bytes& out);

/// Runs work(i) for i in [0, count) on up to hardware_concurrency threads (chunks of a
/// container are independent); the first exception in index order is rethrown.
void parallel_for(std::size_t count, const std::function<void(std::size_t)>& work);

/// The six IMU values and the stamp of one sensor_msgs Imu message.
struct ImuSample {
  std::int64_t stamp_ns = 0;
  double gyro[3] = {0, 0, 0};
  double accel[3] = {0, 0, 0};
};

/// Decodes a ROS 1 serialized sensor_msgs/Imu (little-endian, no padding).
bool decode_ros1_imu(std::span<const unsigned char> data, ImuSample& out);
/// Decodes a CDR (XCDR1, LE or BE encapsulation) sensor_msgs/msg/Imu. Returns false when the
/// data is too short; `error` then says why.
bool decode_cdr_imu(std::span<const unsigned char> data, ImuSample& out, std::string& error);

/// Builds the IMU recording from decoded samples (channels gyro_x..accel_z, time from stamps).
struct ImuColumns {
  std::vector<std::int64_t> stamp_ns;
  std::vector<double> v[6];
  void reserve(std::size_t n) {
    stamp_ns.reserve(n);
    for (auto& c : v) c.reserve(n);
  }
  void append(const ImuColumns& other) {
    stamp_ns.insert(stamp_ns.end(), other.stamp_ns.begin(), other.stamp_ns.end());
    for (int i = 0; i < 6; ++i) v[i].insert(v[i].end(), other.v[i].begin(), other.v[i].end());
  }
  void clear() {
    stamp_ns.clear();
    for (auto& c : v) c.clear();
  }
  void push(const ImuSample& s) {
    stamp_ns.push_back(s.stamp_ns);
    for (int i = 0; i < 3; ++i) v[i].push_back(s.gyro[i]);
    for (int i = 0; i < 3; ++i) v[3 + i].push_back(s.accel[i]);
  }
};

/// Runs decode(k, part) for every chunk k in [0, count) on up to 8 threads (started once) and
/// appends the parts to `out` in chunk order on the calling thread, at most 64 chunks decoded
/// ahead. The parts' storage is reused, so only `out` costs fresh pages; reserve it first. An
/// exception from decode is rethrown: the first one in chunk order.
void decode_chunks(std::size_t count, ImuColumns& out,
                   const std::function<void(std::size_t, ImuColumns&)>& decode);
}  // namespace imunoise::io::detail

namespace imunoise::io::detail {
/// The Recording of decoded Imu messages: channels gyro_x..accel_z (rad/s, m/s^2), time from
/// the stamps relative to the first. Throws InputError (naming the topic) when there are none.
Recording imu_recording(ImuColumns&& columns, std::string source, RecordingFormat format,
                        std::string topic, std::string type);
}  // namespace imunoise::io::detail
