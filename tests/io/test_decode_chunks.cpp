// The chunk pipeline shared by the bag and MCAP readers (detail::decode_chunks): whatever the
// threads do, the parts arrive in chunk order, and a failing chunk reports the first failure in
// chunk order, as reading the chunks one after another would.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "../../src/io/byte_cursor.hpp"  // internal to src/io: the pipeline under test
#include "imunoise/error.hpp"

namespace imunoise::io::detail {
namespace {

// Chunk k holds k % 7 messages (some none), message i stamped k * 1000 + i.
void fake_chunk(std::size_t k, ImuColumns& part) {
  for (std::size_t i = 0; i < k % 7; ++i) {
    ImuSample s;
    s.stamp_ns = static_cast<std::int64_t>(k * 1000 + i);
    for (int c = 0; c < 3; ++c) {
      s.gyro[c] = static_cast<double>(k) + 0.1 * c;
      s.accel[c] = -static_cast<double>(i) - 0.1 * c;
    }
    part.push(s);
  }
}

TEST(DecodeChunks, PartsArriveInChunkOrder) {
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{3}, std::size_t{1000}}) {
    ImuColumns out;
    decode_chunks(count, out, fake_chunk);
    std::size_t n = 0;
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t i = 0; i < k % 7; ++i, ++n) {
        ASSERT_LT(n, out.stamp_ns.size()) << "count " << count;
        ASSERT_EQ(out.stamp_ns[n], static_cast<std::int64_t>(k * 1000 + i)) << "count " << count;
        EXPECT_EQ(out.v[1][n], static_cast<double>(k) + 0.1);
        EXPECT_EQ(out.v[5][n], -static_cast<double>(i) - 0.2);
      }
    }
    EXPECT_EQ(out.stamp_ns.size(), n);
    for (const auto& column : out.v) EXPECT_EQ(column.size(), n);
  }
}

TEST(DecodeChunks, FirstFailureInChunkOrderIsReported) {
  // Chunks 410 and 400 fail; 410 lies within the chunks decoded ahead, so a thread may fail on it
  // first, but 400 is the one to report.
  for (int repeat = 0; repeat < 5; ++repeat) {
    ImuColumns out;
    std::string message;
    try {
      decode_chunks(1000, out, [](std::size_t k, ImuColumns& part) {
        if (k == 400 || k == 410) throw InputError("chunk " + std::to_string(k) + " is corrupt");
        fake_chunk(k, part);
      });
    } catch (const InputError& error) {
      message = error.what();
    }
    EXPECT_EQ(message, "chunk 400 is corrupt");
  }
}

}  // namespace
}  // namespace imunoise::io::detail
