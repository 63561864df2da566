// Decoding sensor_msgs Imu messages (ROS 1 serialization and ROS 2 CDR), the memory map and
// the decompressors shared by the bag and MCAP readers.
#include <bzlib.h>
#include <fcntl.h>
#include <lz4frame.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zstd.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <bit>
#include <exception>
#include <thread>
#include <cerrno>
#include <cstring>

#include "byte_cursor.hpp"

namespace imunoise::io::detail {
namespace {

double f64_at(const unsigned char* p, bool big) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, p, 8);
  if (big != (std::endian::native == std::endian::big)) bits = __builtin_bswap64(bits);
  return std::bit_cast<double>(bits);
}
std::uint32_t u32_at(const unsigned char* p, bool big) {
  std::uint32_t v = 0;
  std::memcpy(&v, p, 4);
  if (big != (std::endian::native == std::endian::big)) v = __builtin_bswap32(v);
  return v;
}

}  // namespace

// Uncompressed sizes are stated by the file: refuse absurd ones before allocating.
static void check_size(std::uint64_t expected, std::size_t compressed, const std::string& where) {
  // bz2, lz4 and zstd cannot expand data by more than ~ 1:1000 (zstd's limit is higher only
  // for degenerate runs); a larger claim is corruption, not an IMU log.
  if (expected > (std::uint64_t{1} << 34) || expected > 2048 * (std::uint64_t{compressed} + 64)) {
    throw InputError(where + ": the stated uncompressed size " + std::to_string(expected) +
                     " bytes is implausible for " + std::to_string(compressed) +
                     " compressed bytes; fix: the file is corrupt, copy it again");
  }
}

void decompress_bz2(std::span<const unsigned char> in, std::uint64_t expected, const std::string& where, Bytes& out) {
  check_size(expected, in.size(), where);
  out.resize_uninitialized(static_cast<std::size_t>(expected));
  unsigned int out_len = static_cast<unsigned int>(expected);
  if (in.size() > 0xffffffffu) throw InputError(where + ": bz2 chunk too large");
  const int rc = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &out_len,
                                            const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                                            static_cast<unsigned int>(in.size()), 0, 0);
  if (rc != BZ_OK || out_len != expected) {
    throw InputError(where + ": bz2 data does not decompress to the stated " + std::to_string(expected) +
                     " bytes (bzip2 error " + std::to_string(rc) + "); fix: the file is corrupt or cut short, copy it again");
  }
}

void decompress_lz4_frame(std::span<const unsigned char> in, std::uint64_t expected, const std::string& where, Bytes& out) {
  check_size(expected, in.size(), where);
  out.resize_uninitialized(static_cast<std::size_t>(expected));
  LZ4F_dctx* ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) {
    throw InputError(where + ": cannot create an lz4 context");
  }
  std::size_t in_pos = 0;
  std::size_t out_pos = 0;
  std::size_t hint = 1;
  while (in_pos < in.size() && hint != 0) {
    std::size_t src = in.size() - in_pos;
    std::size_t dst = out.size() - out_pos;
    hint = LZ4F_decompress(ctx, out.data() + out_pos, &dst, in.data() + in_pos, &src, nullptr);
    if (LZ4F_isError(hint)) {
      const std::string name = LZ4F_getErrorName(hint);
      LZ4F_freeDecompressionContext(ctx);
      throw InputError(where + ": lz4 data is corrupt (" + name + "); fix: copy the file again");
    }
    in_pos += src;
    out_pos += dst;
    if (src == 0 && dst == 0) break;  // no progress: output full or input exhausted
  }
  LZ4F_freeDecompressionContext(ctx);
  if (out_pos != expected || hint != 0) {
    throw InputError(where + ": lz4 data does not decompress to the stated " + std::to_string(expected) +
                     " bytes (got " + std::to_string(out_pos) + "); fix: the file is corrupt or cut short, copy it again");
  }
}

void decompress_zstd(std::span<const unsigned char> in, std::uint64_t expected, const std::string& where, Bytes& out) {
  check_size(expected, in.size(), where);
  out.resize_uninitialized(static_cast<std::size_t>(expected));
  // One context per thread: ZSTD_decompress would allocate and initialise one per chunk.
  struct FreeContext {
    void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
  };
  thread_local const std::unique_ptr<ZSTD_DCtx, FreeContext> context(ZSTD_createDCtx());
  if (!context) throw InputError(where + ": cannot create a zstd context (out of memory)");
  const std::size_t n = ZSTD_decompressDCtx(context.get(), out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n)) {
    throw InputError(where + ": zstd data is corrupt (" + ZSTD_getErrorName(n) + "); fix: copy the file again");
  }
  if (n != expected) {
    throw InputError(where + ": zstd data decompresses to " + std::to_string(n) + " bytes, not the stated " +
                     std::to_string(expected) + "; fix: the file is corrupt, copy it again");
  }
}

void parallel_for(std::size_t count, const std::function<void(std::size_t)>& work) {
  const std::size_t threads = std::min<std::size_t>(count, std::max(1u, std::min(8u, std::thread::hardware_concurrency())));
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  auto run = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < count;) {
      try {
        work(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(run);
  run();
  for (auto& t : pool) t.join();
  for (auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

namespace {

void append_part(ImuColumns& out, const ImuColumns& part) {
  out.stamp_ns.insert(out.stamp_ns.end(), part.stamp_ns.begin(), part.stamp_ns.end());
  for (int i = 0; i < 6; ++i) out.v[i].insert(out.v[i].end(), part.v[i].begin(), part.v[i].end());
}

}  // namespace

void decode_chunks(std::size_t count, ImuColumns& out,
                   const std::function<void(std::size_t, ImuColumns&)>& decode) {
  const std::size_t threads =
      std::min<std::size_t>(count, std::max(1u, std::min(8u, std::thread::hardware_concurrency())));
  if (threads <= 1) {
    ImuColumns part;
    for (std::size_t k = 0; k < count; ++k) {
      part.clear();
      decode(k, part);
      append_part(out, part);
    }
    return;
  }
  // Workers decode chunks up to kWindow ahead of the one this thread appends next (and this
  // thread decodes too whenever that one is not ready). No barrier between batches: on a
  // shared machine a thread that loses the processor must not stall the others.
  constexpr std::size_t kWindow = 64;
  struct Slot {
    ImuColumns part;
    std::exception_ptr error;
    bool done = false;
  };
  std::vector<Slot> slots(std::min(count, kWindow));
  std::mutex mutex;
  std::condition_variable work_ready;
  std::condition_variable chunk_done;
  std::size_t claimed = 0;
  std::size_t taken = 0;
  bool stop = false;
  auto claimable = [&] { return !stop && claimed < count && claimed < taken + slots.size(); };
  auto decode_claimed = [&](std::unique_lock<std::mutex>& lock) {  // lock held on entry and exit
    const std::size_t k = claimed++;
    Slot& slot = slots[k % slots.size()];
    lock.unlock();
    try {
      slot.part.clear();
      decode(k, slot.part);
    } catch (...) {
      slot.error = std::current_exception();
    }
    lock.lock();
    slot.done = true;
    chunk_done.notify_all();
  };
  std::vector<std::thread> workers;
  struct Join {  // also when this thread throws: the workers finish their chunk and leave
    std::vector<std::thread>& workers;
    std::mutex& mutex;
    bool& stop;
    std::condition_variable& work_ready;
    ~Join() {
      {
        std::lock_guard lock(mutex);
        stop = true;
      }
      work_ready.notify_all();
      for (auto& worker : workers) worker.join();
    }
  } join{workers, mutex, stop, work_ready};
  for (std::size_t t = 1; t < threads; ++t) {
    workers.emplace_back([&] {
      std::unique_lock lock(mutex);
      for (;;) {
        work_ready.wait(lock, [&] { return stop || claimed >= count || claimable(); });
        if (!claimable()) return;
        decode_claimed(lock);
      }
    });
  }
  for (std::size_t k = 0; k < count; ++k) {
    Slot& slot = slots[k % slots.size()];
    {
      std::unique_lock lock(mutex);
      while (!slot.done) {
        if (claimable()) {
          decode_claimed(lock);
        } else {
          chunk_done.wait(lock);
        }
      }
    }
    if (slot.error) std::rethrow_exception(slot.error);  // the first error in chunk order
    append_part(out, slot.part);
    {
      std::lock_guard lock(mutex);
      slot.done = false;
      ++taken;
    }
    work_ready.notify_all();
  }
}

// ROS 1: Header{uint32 seq, uint32 sec, uint32 nsec, string frame_id}, then orientation (4
// f64), its covariance (9), angular_velocity (3), covariance (9), linear_acceleration (3),
// covariance (9); little-endian, packed.
bool decode_ros1_imu(std::span<const unsigned char> d, ImuSample& out) {
  if (d.size() < 16) return false;
  const std::uint32_t sec = u32_at(d.data() + 4, false);
  const std::uint32_t nsec = u32_at(d.data() + 8, false);
  const std::uint32_t frame_len = u32_at(d.data() + 12, false);
  const std::size_t body = 16 + std::size_t{frame_len};
  if (frame_len > d.size() || body + (4 + 9 + 3 + 9 + 3 + 9) * 8 > d.size()) return false;
  const unsigned char* p = d.data() + body + (4 + 9) * 8;
  for (int i = 0; i < 3; ++i) out.gyro[i] = f64_at(p + 8 * i, false);
  p += (3 + 9) * 8;
  for (int i = 0; i < 3; ++i) out.accel[i] = f64_at(p + 8 * i, false);
  out.stamp_ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec;
  return true;
}

// CDR (XCDR1): a 4-byte encapsulation header (0x00 0x00 big-endian, 0x00 0x01 little-endian;
// 2 option bytes), then fields aligned to their size relative to the end of that header.
// Header{Time{int32 sec, uint32 nanosec}, string frame_id (uint32 length incl. NUL)}, then the
// same doubles as ROS 1, each 8-aligned.
bool decode_cdr_imu(std::span<const unsigned char> d, ImuSample& out, std::string& error) {
  if (d.size() < 4 + 12) {
    error = "message of " + std::to_string(d.size()) + " bytes is too short for sensor_msgs/msg/Imu";
    return false;
  }
  if (d[0] != 0 || (d[1] != 0 && d[1] != 1)) {
    error = "unsupported CDR encapsulation " + std::to_string(d[0]) + "," + std::to_string(d[1]) +
            " (only plain CDR, little- or big-endian, is read)";
    return false;
  }
  const bool big = d[1] == 0;
  const unsigned char* b = d.data() + 4;
  const std::size_t n = d.size() - 4;
  const std::int32_t sec = static_cast<std::int32_t>(u32_at(b, big));
  const std::uint32_t nsec = u32_at(b + 4, big);
  const std::uint32_t frame_len = u32_at(b + 8, big);
  if (frame_len > n) {
    error = "frame_id length " + std::to_string(frame_len) + " exceeds the message";
    return false;
  }
  std::size_t pos = 12 + std::size_t{frame_len};
  pos = (pos + 7) & ~std::size_t{7};
  if (pos + (4 + 9 + 3 + 9 + 3 + 9) * 8 > n) {
    error = "message of " + std::to_string(d.size()) + " bytes is too short for sensor_msgs/msg/Imu";
    return false;
  }
  const unsigned char* p = b + pos + (4 + 9) * 8;
  for (int i = 0; i < 3; ++i) out.gyro[i] = f64_at(p + 8 * i, big);
  p += (3 + 9) * 8;
  for (int i = 0; i < 3; ++i) out.accel[i] = f64_at(p + 8 * i, big);
  out.stamp_ns = std::int64_t{sec} * 1'000'000'000 + nsec;
  return true;
}

}  // namespace imunoise::io::detail
