// libFuzzer target for the text reader: for any bytes the reader must either return columns or
// throw InputError; anything else (a crash, a sanitizer report, another exception, a leak, a
// hang) is a bug.
//
// Every input is also read with the bulk row parser off (the plain line-by-line read) and, for
// the buffer path, with 1-3 threads: values, times, lines and error messages must be identical.
//
// Input layout: byte 0 chooses the options (so the fuzzer explores them too), the rest is the
// file content.
//   bits 0-1  value column: none, index (byte 0 >> 6), name "x", name "gx"
//   bits 2-3  time column: none, index 0, name "t", index 1
//   bits 4-5  input path: in-memory buffer, or a stream read in blocks of 1, 7 or 4096 bytes
//   bit  6    time unit given as ns (else auto-detected)
//   bit  7    also analyse the timestamps (rate, gaps, disorder)
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "imunoise/error.hpp"
#include "imunoise/io/text_reader.hpp"
#include "imunoise/io/timestamps.hpp"

namespace {

imunoise::io::TextReadOptions options_from(std::uint8_t bits) {
  using imunoise::io::ColumnSelector;
  imunoise::io::TextReadOptions options;
  switch (bits & 3u) {
    case 1: options.column = ColumnSelector(static_cast<std::size_t>(bits >> 6u)); break;
    case 2: options.column = ColumnSelector(std::string("x")); break;
    case 3: options.column = ColumnSelector(std::string("gx")); break;
    default: break;
  }
  switch ((bits >> 2u) & 3u) {
    case 1: options.time_column = ColumnSelector(std::size_t{0}); break;
    case 2: options.time_column = ColumnSelector(std::string("t")); break;
    case 3: options.time_column = ColumnSelector(std::size_t{1}); break;
    default: break;
  }
  if (bits & 0x40u) options.time_unit = imunoise::parse_unit("ns");
  return options;
}

// The outcome of one read: the columns, or the error message.
struct Outcome {
  std::optional<imunoise::io::TextColumns> columns;
  std::string error;
};

Outcome read(std::string_view text, imunoise::io::TextReadOptions options, unsigned path) {
  Outcome out;
  try {
    if (path == 0) {
      out.columns = imunoise::io::read_text_buffer(text, "fuzz", options);
    } else {
      constexpr std::size_t block_sizes[] = {0, 1, 7, 4096};
      options.block_bytes = block_sizes[path];
      std::istringstream in{std::string(text)};
      out.columns = imunoise::io::read_text_stream(in, "fuzz", options);
    }
  } catch (const imunoise::InputError& error) {
    out.error = error.what();
  }
  return out;
}

bool same_doubles(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Bulk and line-by-line reads must agree to the bit and to the letter.
void check_same(const Outcome& a, const Outcome& b) {
  if (a.error != b.error || a.columns.has_value() != b.columns.has_value()) __builtin_trap();
  if (!a.columns) return;
  const auto& x = *a.columns;
  const auto& y = *b.columns;
  if (!same_doubles(x.values, y.values) || !same_doubles(x.time_s, y.time_s)) __builtin_trap();
  if (x.header != y.header || x.first_data_line != y.first_data_line ||
      x.time_origin != y.time_origin) {
    __builtin_trap();
  }
  for (std::size_t i = 0; i < x.values.size(); ++i) {
    if (x.line_of(i) != y.line_of(i)) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t bits = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  imunoise::io::TextReadOptions options = options_from(bits);
  try {
    imunoise::io::TextColumns columns;
    const unsigned path = (bits >> 4u) & 3u;
    if (path == 0) {
      columns = imunoise::io::read_text_buffer(text, "fuzz", options);
    } else {
      constexpr std::size_t block_sizes[] = {0, 1, 7, 4096};
      options.block_bytes = block_sizes[path];
      std::istringstream in{std::string(text)};
      columns = imunoise::io::read_text_stream(in, "fuzz", options);
    }
    // Invariants of a successful read.
    if (columns.values.empty()) __builtin_trap();
    if (!columns.time_s.empty() && columns.time_s.size() != columns.values.size()) __builtin_trap();
    if (columns.line_of(columns.values.size() - 1) < columns.first_data_line) __builtin_trap();
    if ((bits & 0x80u) && !columns.time_s.empty()) {
      (void)imunoise::io::check_timing(columns.time_s, columns.source, &columns.lines, true);
    }
  } catch (const imunoise::InputError&) {
    // The expected outcome for invalid input.
  }
  // Differential check of the bulk row parser (on by default above) against the plain read.
  const unsigned path = (bits >> 4u) & 3u;
  options.bulk_rows = false;
  const Outcome plain = read(text, options, path);
  options.bulk_rows = true;
  for (const unsigned threads : {1u, 2u, 3u}) {
    options.threads = threads;
    check_same(read(text, options, path), plain);
    if (path != 0) break;  // the stream paths' tiny blocks make threads moot
  }
  return 0;
}
