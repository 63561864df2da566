// The bulk row parser (byte ranges parsed side by side) against the plain line-by-line read:
// the same values bit for bit, the same line of every sample, the same error message (line
// number and row index included), whatever the thread count and block size.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <functional>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "imunoise/error.hpp"
#include "imunoise/io/text_reader.hpp"
#include "io_test_support.hpp"

namespace imunoise::io {
namespace {

using test::TempDir;

std::vector<std::uint64_t> bits(const std::vector<double>& values) {
  std::vector<std::uint64_t> out;
  out.reserve(values.size());
  for (const double v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
  return out;
}

// Rows "t,gx,gy" (or the given separator) in %.9e and other forms, with some irregular lines
// (comments, blanks, quotes, '+' signs, NaN in an unused column, spaces, CRLF) sprinkled in,
// as a file has them; the line-by-line parser takes those, the bulk parser the rest.
std::string mixed_text(std::size_t rows, char separator, bool crlf, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const std::string eol = crlf ? "\r\n" : "\n";
  const std::string s(1, separator);
  std::string text = "# recorded by a test" + eol + "t" + s + "gx" + s + "gy" + eol;
  char cell[64];
  for (std::size_t i = 0; i < rows; ++i) {
    std::string row;
    for (int c = 0; c < 3; ++c) {
      const double v = c == 0 ? static_cast<double>(i) * 0.005 : gaussian(engine) * 1e-3;
      const char* format = (i % 5 == 0) ? "%.17g" : (i % 7 == 0 ? "%.3f" : "%.9e");
      std::snprintf(cell, sizeof cell, format, v);
      if (c > 0) row += s;
      row += cell;
    }
    switch (i % 997) {
      case 3: row += " # trailing comment"; break;
      case 5: text += eol; break;                          // blank line
      case 8: row = " " + row + "  "; break;               // blanks around the row
      case 13: row = "\"" + row.substr(0, row.find(separator)) + "\"" +
                     row.substr(row.find(separator)); break;  // quoted cell
      case 21: row = "+" + row; break;                      // leading '+'
      case 34: row = "nan" + row.substr(row.find(separator)); break;  // NaN in the time column
      default: break;
    }
    text += row + eol;
  }
  return text;
}

TextReadOptions options_for(bool bulk, unsigned threads, std::size_t block) {
  TextReadOptions options;
  options.column = std::string("gy");
  options.bulk_rows = bulk;
  options.threads = threads;
  options.block_bytes = block;
  return options;
}

void expect_same(const TextColumns& a, const TextColumns& b, const std::string& what) {
  ASSERT_EQ(a.values.size(), b.values.size()) << what;
  EXPECT_EQ(bits(a.values), bits(b.values)) << what;
  EXPECT_EQ(a.header, b.header) << what;
  EXPECT_EQ(a.header_line, b.header_line) << what;
  EXPECT_EQ(a.first_data_line, b.first_data_line) << what;
  EXPECT_EQ(a.column_count, b.column_count) << what;
  EXPECT_EQ(bits(a.time_s), bits(b.time_s)) << what;
  EXPECT_EQ(a.time_origin, b.time_origin) << what;
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    if (a.line_of(i) != b.line_of(i)) {
      ADD_FAILURE() << what << ": sample " << i << " on line " << a.line_of(i) << " vs "
                    << b.line_of(i);
      break;
    }
  }
}

std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(TextReaderBulk, SameValuesAndLinesAsLineByLineForAnyThreadsAndBlock) {
  for (const char separator : {',', ';', '\t', ' '}) {
    for (const bool crlf : {false, true}) {
      const std::string text = mixed_text(60000, separator, crlf, 3);
      const auto reference = read_text_buffer(text, "mem", options_for(false, 1, 1 << 20));
      ASSERT_GT(reference.values.size(), 59000u);
      for (const unsigned threads : {1u, 2u, 3u, 7u}) {
        for (const std::size_t block : {std::size_t{4096}, std::size_t{1} << 20}) {
          const auto bulk = read_text_buffer(text, "mem", options_for(true, threads, block));
          expect_same(bulk, reference,
                      "separator '" + std::string(1, separator) + "' crlf " +
                          std::to_string(crlf) + " threads " + std::to_string(threads) +
                          " block " + std::to_string(block));
        }
      }
    }
  }
}

TEST(TextReaderBulk, FileWithTimeColumnMatchesLineByLine) {
  TempDir dir;
  const auto file = dir.write("imu.csv", mixed_text(120000, ',', false, 4));
  for (const unsigned threads : {1u, 2u, 4u}) {
    auto with_time = [&](bool bulk) {
      TextReadOptions options = options_for(bulk, threads, 1 << 20);
      options.column = std::string("gx");
      options.time_column = std::string("t");
      return options;
    };
    // The NaN in the time column stops both reads at the same line with the same message.
    const std::string serial = message_of([&] { read_text_file(file, with_time(false)); });
    EXPECT_NE(serial.find("imu.csv:"), std::string::npos) << serial;
    EXPECT_EQ(message_of([&] { read_text_file(file, with_time(true)); }), serial);
    // Without the NaN row, the whole file reads the same.
    std::string clean = mixed_text(120000, ',', false, 4);
    for (std::size_t at = clean.find("\nnan"); at != std::string::npos; at = clean.find("\nnan")) {
      clean.replace(at + 1, 3, "1.0");
    }
    const auto clean_file = dir.write("clean.csv", clean);
    expect_same(read_text_file(clean_file, with_time(true)), read_text_file(clean_file, with_time(false)),
                "time column, threads " + std::to_string(threads));
  }
}

// Every kind of bad row, early, in the middle of a block, in the second half of a block and on
// the last line: the bulk read throws the line-by-line read's message, line number included.
TEST(TextReaderBulk, ErrorsCarryTheExactLineNumber) {
  const std::size_t rows = 40000;
  std::string base = "t,gx,gy\n";
  char row[96];
  for (std::size_t i = 0; i < rows; ++i) {
    std::snprintf(row, sizeof row, "%.9e,%.9e,%.9e\n", static_cast<double>(i) * 0.005,
                  1e-3 * std::sin(static_cast<double>(i)), -1e-3 * std::cos(static_cast<double>(i)));
    base += row;
  }
  struct Bad {
    std::string cell;       // replaces the gy (or gx) cell
    bool value_column;      // gy (read) or gx (checked only)
    std::string fragment;   // in the message
  };
  const std::vector<Bad> bads{{"abc", true, "is not a number"},  {"", true, "empty cell"},
                              {"nan", true, "is NaN or Inf"},     {"1e999", true, "outside the range"},
                              {"1.5x", false, "is not a number"}, {"1,2", true, "fields"},
                              {"--1", false, "is not a number"}};
  for (const std::size_t line : {std::size_t{2}, std::size_t{3}, std::size_t{9000},
                                 std::size_t{23000}, rows + 1}) {
    for (const Bad& bad : bads) {
      // Lines are 1-based and line 1 is the header: data line L holds sample L - 2.
      std::string text = base;
      std::size_t begin = 0;
      for (std::size_t l = 1; l < line; ++l) begin = text.find('\n', begin) + 1;
      const std::size_t end = text.find('\n', begin);
      const std::string original = text.substr(begin, end - begin);
      const std::size_t c1 = original.find(','), c2 = original.rfind(',');
      const std::string edited = bad.value_column
                                     ? original.substr(0, c2 + 1) + bad.cell
                                     : original.substr(0, c1 + 1) + bad.cell + original.substr(c2);
      text.replace(begin, end - begin, edited);
      if (line == rows + 1) text.pop_back();  // last line without its newline
      const std::string serial =
          message_of([&] { read_text_buffer(text, "f.csv", options_for(false, 1, 1 << 20)); });
      EXPECT_NE(serial.find("f.csv:" + std::to_string(line) + ":"), std::string::npos)
          << serial;
      EXPECT_NE(serial.find(bad.fragment), std::string::npos) << serial;
      for (const unsigned threads : {1u, 2u, 5u}) {
        for (const std::size_t block : {std::size_t{1000}, std::size_t{1} << 20}) {
          EXPECT_EQ(message_of([&] {
                      read_text_buffer(text, "f.csv", options_for(true, threads, block));
                    }),
                    serial)
              << "line " << line << " cell '" << bad.cell << "' threads " << threads;
        }
      }
    }
  }
}

// Cells at the edges of the number grammar, in the value column and in a checked column: the
// bulk parser's own scan and fast conversion must accept, convert (bit for bit) and reject
// exactly as parse_number does, or leave the line to the line parser.
TEST(TextReaderBulk, NumberEdgeCasesAgreeWithParseNumber) {
  const std::vector<std::string> cells{
      "1.", ".5", "-.5", "+.5", "1.e5", "-1.E-5", "+1e+5", "0", "-0", "-0.0", "00012.5000",
      "1e22", "1e23", "9007199254740993", "9007199254740992", "123456789012345678901234",
      "1e-22", "1e-23", "4.9e-324", "2.2250738585072014e-308", "1.7976931348623157e308",
      "1e308", "1e309", "1e-400", "0.1", "0.3", "3.141592653589793238", "1e0000000000000001",
      ".", "-", "+", "e5", "1e", "1e+", "--1", "+-1", "1..2", "1.2.3", "0x10", "1,5", "1_0",
      "inf", "nan", "-inf", "Infinity", "1e5x", "١", " 1", "1 "};
  std::string header = "a,b\n";
  for (const std::string& cell : cells) {
    for (const bool value_column : {true, false}) {
      std::string text = header;
      for (int i = 0; i < 3; ++i) text += "2.5,7.25\n";
      text += value_column ? "3.5," + cell + "\n" : cell + ",8.5\n";
      for (int i = 0; i < 3; ++i) text += "4.5,9.75\n";
      TextReadOptions serial;
      serial.column = std::string("b");
      serial.bulk_rows = false;
      TextReadOptions bulk = serial;
      bulk.bulk_rows = true;
      std::string serial_error, bulk_error;
      std::vector<double> serial_values, bulk_values;
      try {
        serial_values = read_text_buffer(text, "e.csv", serial).values;
      } catch (const InputError& error) {
        serial_error = error.what();
      }
      try {
        bulk_values = read_text_buffer(text, "e.csv", bulk).values;
      } catch (const InputError& error) {
        bulk_error = error.what();
      }
      EXPECT_EQ(bulk_error, serial_error) << "cell '" << cell << "'";
      EXPECT_EQ(bits(bulk_values), bits(serial_values)) << "cell '" << cell << "'";
      if (value_column && serial_error.empty()) {
        ASSERT_EQ(serial_values.size(), 7u);
        const std::size_t first = cell.find_first_not_of(' ');
        const auto parsed = parse_number(cell.substr(first, cell.find_last_not_of(' ') + 1 - first));
        ASSERT_TRUE(parsed.has_value()) << cell;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(serial_values[3]), std::bit_cast<std::uint64_t>(*parsed));
      }
    }
  }
}

}  // namespace
}  // namespace imunoise::io
