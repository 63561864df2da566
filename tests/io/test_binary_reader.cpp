// Binary reader: every format x byte order x interleaving round-trips exactly; streaming in any
// chunk size equals reading all; each error path names the record and says the fix.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "imunoise/io/binary_reader.hpp"
#include "io_test_support.hpp"

namespace imunoise::io {
namespace {

using test::expect_input_error;
using test::TempDir;

// An encoder written independently of the reader: bytes are produced by shifting, most or
// least significant first, so the test does not depend on the host's byte order.
template <class Unsigned>
void put_bytes(std::string& out, Unsigned bits, std::size_t size, ByteOrder order) {
  for (std::size_t i = 0; i < size; ++i) {
    const std::size_t shift = 8 * (order == ByteOrder::little ? i : size - 1 - i);
    out += static_cast<char>(static_cast<unsigned char>((bits >> shift) & 0xffu));
  }
}

void put_sample(std::string& out, double value, BinaryFormat format) {
  switch (format.type) {
    case SampleType::f32:
      put_bytes(out, std::bit_cast<std::uint32_t>(static_cast<float>(value)), 4, format.order);
      break;
    case SampleType::f64:
      put_bytes(out, std::bit_cast<std::uint64_t>(value), 8, format.order);
      break;
    case SampleType::i16:
      put_bytes(out, static_cast<std::uint16_t>(static_cast<std::int16_t>(value)), 2, format.order);
      break;
    case SampleType::i32:
      put_bytes(out, static_cast<std::uint32_t>(static_cast<std::int32_t>(value)), 4, format.order);
      break;
  }
}

// value of channel c in record r: exactly representable in every format (integers within
// int16 range, and sign changes), plus a fractional part for the float formats.
double sample_value(std::size_t r, std::size_t c, SampleType type) {
  const double integer = static_cast<double>((static_cast<long>(r * 7919 + c * 104729) % 65535) - 32767);
  const bool is_float = type == SampleType::f32 || type == SampleType::f64;
  return is_float ? integer + 0.25 * static_cast<double>(c) : integer;
}

std::string encode(std::size_t records, std::size_t channels, BinaryFormat format) {
  std::string bytes;
  for (std::size_t r = 0; r < records; ++r) {
    for (std::size_t c = 0; c < channels; ++c) put_sample(bytes, sample_value(r, c, format.type), format);
  }
  return bytes;
}

struct FormatCase {
  SampleType type;
  ByteOrder order;
};

class BinaryRoundTrip : public ::testing::TestWithParam<FormatCase> {};

TEST_P(BinaryRoundTrip, EveryChannelOfInterleavedRecords) {
  const BinaryFormat format{GetParam().type, GetParam().order};
  constexpr std::size_t records = 1000;
  constexpr std::size_t channels = 3;
  TempDir dir;
  const auto path = dir.write("data.bin", encode(records, channels, format));
  for (std::size_t c = 0; c < channels; ++c) {
    BinaryReadOptions options;
    options.format = format;
    options.channels = channels;
    options.column = c;
    options.chunk_bytes = 4096;
    const std::vector<double> values = read_binary_file(path, options);
    ASSERT_EQ(values.size(), records);
    for (std::size_t r = 0; r < records; ++r) {
      ASSERT_EQ(values[r], sample_value(r, c, format.type)) << binary_format_name(format) << " r=" << r;
    }
  }
}

TEST_P(BinaryRoundTrip, SingleChannelFromAStream) {
  const BinaryFormat format{GetParam().type, GetParam().order};
  std::istringstream in(encode(257, 1, format));
  BinaryReadOptions options;
  options.format = format;
  options.chunk_bytes = 5;  // smaller than one sample of f64: one record per chunk
  const auto values = read_binary_stream(in, "<stdin>", options);
  ASSERT_EQ(values.size(), 257u);
  for (std::size_t r = 0; r < values.size(); ++r) EXPECT_EQ(values[r], sample_value(r, 0, format.type));
}

INSTANTIATE_TEST_SUITE_P(
    AllFormats, BinaryRoundTrip,
    ::testing::Values(FormatCase{SampleType::f32, ByteOrder::little},
                      FormatCase{SampleType::f32, ByteOrder::big},
                      FormatCase{SampleType::f64, ByteOrder::little},
                      FormatCase{SampleType::f64, ByteOrder::big},
                      FormatCase{SampleType::i16, ByteOrder::little},
                      FormatCase{SampleType::i16, ByteOrder::big},
                      FormatCase{SampleType::i32, ByteOrder::little},
                      FormatCase{SampleType::i32, ByteOrder::big}),
    [](const auto& p) {
      std::string name = binary_format_name({p.param.type, p.param.order});
      name[3] = '_';
      return name;
    });

TEST(BinaryReader, ExtremeIntegersAndFloatBitsSurvive) {
  std::string bytes;
  const BinaryFormat i16_be{SampleType::i16, ByteOrder::big};
  put_bytes(bytes, std::uint16_t{0x8000}, 2, ByteOrder::big);  // -32768
  put_bytes(bytes, std::uint16_t{0x7fff}, 2, ByteOrder::big);  // 32767
  std::istringstream in(bytes);
  BinaryReadOptions options;
  options.format = i16_be;
  EXPECT_EQ(read_binary_stream(in, "s", options), (std::vector<double>{-32768.0, 32767.0}));

  std::string f64_bytes;
  const double tiny = std::numeric_limits<double>::denorm_min();
  put_bytes(f64_bytes, std::bit_cast<std::uint64_t>(tiny), 8, ByteOrder::big);
  put_bytes(f64_bytes, std::bit_cast<std::uint64_t>(-0.1), 8, ByteOrder::big);
  std::istringstream in64(f64_bytes);
  options.format = {SampleType::f64, ByteOrder::big};
  EXPECT_EQ(read_binary_stream(in64, "s", options), (std::vector<double>{tiny, -0.1}));
}

TEST(BinaryReader, StreamingInAnyChunkEqualsReadAll) {
  const BinaryFormat format{SampleType::f32, ByteOrder::little};
  TempDir dir;
  const auto path = dir.write("big.f32", encode(100'000, 2, format));
  BinaryReadOptions options;
  options.format = format;
  options.channels = 2;
  options.column = 1;
  const auto all = read_binary_file(path, options);
  ASSERT_EQ(all.size(), 100'000u);
  for (std::size_t span_size : {std::size_t{1}, std::size_t{3}, std::size_t{4096}, std::size_t{99'999}}) {
    options.chunk_bytes = 1000;
    BinaryReader reader(path, options);
    EXPECT_EQ(reader.record_count(), std::optional<std::size_t>(100'000));
    std::vector<double> collected;
    std::vector<double> buffer(span_size);
    while (const std::size_t n = reader.read(buffer)) {
      collected.insert(collected.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n));
    }
    EXPECT_EQ(collected, all) << span_size;
    EXPECT_EQ(reader.records_read(), 100'000u);
    EXPECT_EQ(reader.read(buffer), 0u);
  }
}

TEST(BinaryReader, ScaleConvertsCounts) {
  std::string bytes;
  const BinaryFormat format{SampleType::i16, ByteOrder::little};
  for (int count : {-4, 0, 3}) put_sample(bytes, count, format);
  std::istringstream in(bytes);
  BinaryReadOptions options;
  options.format = format;
  options.scale = 0.5;  // e.g. 0.5 deg/s per count
  EXPECT_EQ(read_binary_stream(in, "adc", options), (std::vector<double>{-2.0, 0.0, 1.5}));
}

TEST(BinaryReader, FormatNamesAndExtensions) {
  EXPECT_EQ(parse_binary_format("f64"), (BinaryFormat{SampleType::f64, ByteOrder::little}));
  EXPECT_EQ(parse_binary_format("i16:be"), (BinaryFormat{SampleType::i16, ByteOrder::big}));
  EXPECT_EQ(parse_binary_format("f32:le"), (BinaryFormat{SampleType::f32, ByteOrder::little}));
  for (SampleType type : {SampleType::f32, SampleType::f64, SampleType::i16, SampleType::i32}) {
    for (ByteOrder order : {ByteOrder::little, ByteOrder::big}) {
      const BinaryFormat format{type, order};
      EXPECT_EQ(parse_binary_format(binary_format_name(format)), format);
    }
  }
  EXPECT_EQ(BinaryFormat{SampleType::i16}.sample_bytes(), 2u);
  EXPECT_EQ(BinaryFormat{SampleType::f64}.sample_bytes(), 8u);
  expect_input_error([] { parse_binary_format("f16"); }, {"'f16'", "f32, f64, i16 or i32"});
  expect_input_error([] { parse_binary_format("f32:xe"); }, {"'xe'", ":le or :be"});
  EXPECT_EQ(binary_format_from_extension("a/b/gyro.f32"), parse_binary_format("f32"));
  EXPECT_EQ(binary_format_from_extension("gyro.I16"), parse_binary_format("i16"));
  EXPECT_EQ(binary_format_from_extension("gyro.i32"), parse_binary_format("i32:le"));
  EXPECT_EQ(binary_format_from_extension("gyro.f64"), parse_binary_format("f64"));
  EXPECT_EQ(binary_format_from_extension("gyro.bin"), std::nullopt);
  EXPECT_EQ(binary_format_from_extension("gyro.csv"), std::nullopt);
  EXPECT_EQ(binary_format_from_extension("gyro"), std::nullopt);
}

// --- errors --------------------------------------------------------------------------------------

TEST(BinaryReaderErrors, TruncatedFile) {
  const BinaryFormat format{SampleType::f64, ByteOrder::little};
  TempDir dir;
  const auto path = dir.write("cut.bin", encode(10, 3, format) + std::string(5, '\0'));
  BinaryReadOptions options;
  options.format = format;
  options.channels = 3;
  expect_input_error([&] { BinaryReader reader(path, options); },
                     {path.string() + ":", "truncated: 5 trailing byte(s)", "10 complete record(s)",
                      "record 10", "24 bytes per record", "--channels"});
}

TEST(BinaryReaderErrors, TruncatedStream) {
  const BinaryFormat format{SampleType::i32, ByteOrder::big};
  std::istringstream in(encode(7, 2, format) + std::string(6, '\x01'));
  BinaryReadOptions options;
  options.format = format;
  options.channels = 2;
  expect_input_error([&] { read_binary_stream(in, "<stdin>", options); },
                     {"<stdin>:", "truncated: 6 trailing byte(s)", "record 7"});
}

TEST(BinaryReaderErrors, ColumnAndChannels) {
  TempDir dir;
  const auto path = dir.write("x.f32", std::string(24, '\0'));
  BinaryReadOptions options;
  options.format = parse_binary_format("f32");
  options.channels = 3;
  options.column = 3;
  expect_input_error([&] { BinaryReader reader(path, options); },
                     {"x.f32:", "--column 3", "3 channel(s)", "0..2"});
  options.channels = 0;
  options.column = 0;
  expect_input_error([&] { BinaryReader reader(path, options); }, {"--channels 0"});
}

TEST(BinaryReaderErrors, EmptyInput) {
  TempDir dir;
  const auto path = dir.write("empty.f64", "");
  expect_input_error([&] { BinaryReader reader(path, {}); }, {"empty.f64:", "empty"});
  std::istringstream in("");
  expect_input_error([&] { read_binary_stream(in, "<stdin>", {}); }, {"<stdin>:", "empty"});
}

TEST(BinaryReaderErrors, NanAndInfNameTheRecord) {
  for (SampleType type : {SampleType::f32, SampleType::f64}) {
    const BinaryFormat format{type, ByteOrder::little};
    std::string bytes;
    for (int r = 0; r < 5; ++r) {
      put_sample(bytes, r == 3 ? std::numeric_limits<double>::quiet_NaN() : 1.0, format);
      put_sample(bytes, r == 1 ? std::numeric_limits<double>::infinity() : 2.0, format);
    }
    TempDir dir;
    const auto path = dir.write("nan.bin", bytes);
    BinaryReadOptions options;
    options.format = format;
    options.channels = 2;
    expect_input_error([&] { read_binary_file(path, options); },
                       {"nan.bin:", "record 3", "column 0", "NaN or Inf"});
    options.column = 1;
    expect_input_error([&] { read_binary_file(path, options); },
                       {"record 1", "column 1", "NaN or Inf"});
  }
}

// One native-order channel is decoded straight from the file's mapping by a plain loop: the
// NaN far into the file is still named by its record, and a seek reads the slice after it.
TEST(BinaryReaderErrors, NanInALongSingleChannelFileNamesTheRecord) {
  const BinaryFormat format{SampleType::f64, ByteOrder::little};
  std::string bytes;
  for (std::size_t r = 0; r < 100'000; ++r) {
    put_sample(bytes, r == 70'001 ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(r), format);
  }
  TempDir dir;
  const auto path = dir.write("long.f64", bytes);
  BinaryReadOptions options;
  options.format = format;
  expect_input_error([&] { read_binary_file(path, options); },
                     {"long.f64:", "record 70001", "byte offset 560008", "NaN or Inf"});
  BinaryReader reader(path, options);
  reader.seek(70'002);
  std::vector<double> slice(10);
  ASSERT_EQ(reader.read(slice), 10u);
  for (std::size_t i = 0; i < slice.size(); ++i) EXPECT_EQ(slice[i], static_cast<double>(70'002 + i));
}

TEST(BinaryReaderErrors, NanInAnUnselectedChannelIsTolerated) {
  const BinaryFormat format{SampleType::f64, ByteOrder::little};
  std::string bytes;
  put_sample(bytes, std::numeric_limits<double>::quiet_NaN(), format);
  put_sample(bytes, 1.5, format);
  std::istringstream in(bytes);
  BinaryReadOptions options;
  options.format = format;
  options.channels = 2;
  options.column = 1;
  EXPECT_EQ(read_binary_stream(in, "s", options), std::vector<double>{1.5});
}

TEST(BinaryReaderErrors, BadScale) {
  BinaryReadOptions options;
  options.scale = 0.0;
  std::istringstream in(std::string(8, '\0'));
  expect_input_error([&] { BinaryReader reader(in, "s", options); }, {"scale factor"});
  options.format = parse_binary_format("f64");
  options.scale = 1e300;
  std::string bytes;
  put_sample(bytes, 1e10, options.format);
  std::istringstream big(bytes);
  expect_input_error([&] { read_binary_stream(big, "s", options); }, {"record 0", "overflows"});
}

TEST(BinaryReaderErrors, MissingFile) {
  TempDir dir;
  expect_input_error([&] { BinaryReader reader(dir.path() / "none.f32", {}); }, {"cannot open"});
  expect_input_error([&] { BinaryReader reader(dir.path(), {}); }, {"is a directory"});
}

}  // namespace
}  // namespace imunoise::io
