// Text reader: formats, exact parsing, column selection, every error path, block independence.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "imunoise/io/text_reader.hpp"
#include "io_test_support.hpp"

namespace imunoise::io {
namespace {

using test::expect_input_error;
using test::TempDir;

TextReadOptions column(ColumnSelector selector) {
  TextReadOptions options;
  options.column = std::move(selector);
  return options;
}

std::vector<double> read_values(std::string_view text, const TextReadOptions& options = {}) {
  return read_text_buffer(text, "mem.csv", options).values;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// --- separators, header, comments, line endings ------------------------------------------------

TEST(TextReader, SingleColumnNeedsNoSelection) {
  const auto r = read_text_buffer("1\n2.5\n-3e2\n", "one.txt");
  EXPECT_EQ(r.values, (std::vector<double>{1.0, 2.5, -300.0}));
  EXPECT_EQ(r.column_count, 1u);
  EXPECT_TRUE(r.header.empty());
  EXPECT_EQ(r.first_data_line, 1u);
  EXPECT_TRUE(r.time_s.empty());
}

struct SeparatorCase {
  const char* text;
  Separator separator;
};

class SeparatorDetection : public ::testing::TestWithParam<SeparatorCase> {};

TEST_P(SeparatorDetection, ReadsTheSecondColumn) {
  const auto r = read_text_buffer(GetParam().text, "sep.txt", column(std::size_t{1}));
  EXPECT_EQ(r.separator, GetParam().separator);
  EXPECT_EQ(r.column_count, 3u);
  EXPECT_EQ(r.values, (std::vector<double>{2.0, 5.0}));
}

INSTANTIATE_TEST_SUITE_P(
    EachSeparator, SeparatorDetection,
    ::testing::Values(SeparatorCase{"1,2,3\n4,5,6\n", Separator::comma},
                      SeparatorCase{"1, 2 , 3\n4 ,5, 6\n", Separator::comma},
                      SeparatorCase{"1\t2\t3\n4\t5\t6\n", Separator::tab},
                      SeparatorCase{"1;2;3\n4;5;6\n", Separator::semicolon},
                      SeparatorCase{"1 2 3\n4 5 6\n", Separator::whitespace},
                      // Tabs mixed with spaces for alignment: runs of blanks separate.
                      SeparatorCase{"  1   2  \t 3  \n4 \t5    6\n", Separator::whitespace}));

TEST(TextReader, TabSeparatedHeaderWithSpacesInNames) {
  const auto r = read_text_buffer("time s\tgyro x\tgyro y\n0\t1\t2\n", "t.tsv",
                                  column(std::string("gyro y")));
  EXPECT_EQ(r.separator, Separator::tab);
  EXPECT_EQ(r.header, (std::vector<std::string>{"time s", "gyro x", "gyro y"}));
  EXPECT_EQ(r.values, std::vector<double>{2.0});
}

TEST(TextReader, SeparatorNames) {
  EXPECT_EQ(separator_name(Separator::comma), "comma");
  EXPECT_EQ(separator_name(Separator::tab), "tab");
  EXPECT_EQ(separator_name(Separator::semicolon), "semicolon");
  EXPECT_EQ(separator_name(Separator::whitespace), "whitespace");
}

TEST(TextReader, HeaderAndColumnByName) {
  const std::string text = "time,gyro_x,gyro_y\n0,0.1,0.2\n0.005,0.3,0.4\n";
  const auto r = read_text_buffer(text, "imu.csv", column(std::string("gyro_y")));
  EXPECT_EQ(r.header, (std::vector<std::string>{"time", "gyro_x", "gyro_y"}));
  EXPECT_EQ(r.header_line, 1u);
  EXPECT_EQ(r.first_data_line, 2u);
  EXPECT_EQ(r.value_column, 2u);
  EXPECT_EQ(r.values, (std::vector<double>{0.2, 0.4}));
  // The same column by 0-based index.
  EXPECT_EQ(read_values(text, column(std::size_t{2})), r.values);
}

TEST(TextReader, QuotedHeaderNames) {
  const auto r = read_text_buffer("\"t\",\"gyro x\"\n1,2\n", "q.csv", column(std::string("gyro x")));
  EXPECT_EQ(r.header, (std::vector<std::string>{"t", "gyro x"}));
  EXPECT_EQ(r.values, (std::vector<double>{2.0}));
}

TEST(TextReader, ParseColumnSelector) {
  EXPECT_EQ(parse_column_selector("3"), ColumnSelector(std::size_t{3}));
  EXPECT_EQ(parse_column_selector(" 0 "), ColumnSelector(std::size_t{0}));
  EXPECT_EQ(parse_column_selector("gyro_x"), ColumnSelector(std::string("gyro_x")));
  EXPECT_EQ(parse_column_selector("3a"), ColumnSelector(std::string("3a")));
  EXPECT_EQ(describe_column_selector(std::size_t{3}), "column 3");
  EXPECT_EQ(describe_column_selector(std::string("gx")), "column \"gx\"");
  expect_input_error([] { parse_column_selector("  "); }, {"--column"});
  expect_input_error([] { parse_column_selector("99999999999999999999999"); }, {"too large"});
}

TEST(TextReader, CommentsAndBlankLines) {
  const std::string text =
      "# recorded 2024-01-01\n"
      "\n"
      "t gx   # header with a comment\n"
      "# another comment\n"
      "0 1.5\n"
      "   \n"
      "1 2.5 # trailing comment\n"
      "#\n"
      "2 3.5\n";
  const auto r = read_text_buffer(text, "c.txt", column(std::string("gx")));
  EXPECT_EQ(r.values, (std::vector<double>{1.5, 2.5, 3.5}));
  EXPECT_EQ(r.header_line, 3u);
  EXPECT_EQ(r.first_data_line, 5u);
  EXPECT_EQ(r.line_of(0), 5u);
  EXPECT_EQ(r.line_of(1), 7u);
  EXPECT_EQ(r.line_of(2), 9u);
}

TEST(TextReader, LineEndingsAndByteOrderMark) {
  const std::vector<double> expected{1.0, 2.0, 3.0};
  EXPECT_EQ(read_values("1\r\n2\r\n3\r\n"), expected);
  EXPECT_EQ(read_values("1\r\n2\r\n3"), expected);
  EXPECT_EQ(read_values("1\r2\r3\r"), expected);  // classic Mac
  EXPECT_EQ(read_values("1\n2\n3"), expected);    // no final newline
  EXPECT_EQ(read_values("\xEF\xBB\xBF" "1\n2\n3\n"), expected);
  const auto r = read_text_buffer("\xEF\xBB\xBFx,y\r\n1,2\r\n", "bom.csv", column(std::string("x")));
  EXPECT_EQ(r.header.front(), "x");
  EXPECT_EQ(r.values, std::vector<double>{1.0});
  // Line numbers count CR-only lines too.
  EXPECT_EQ(read_text_buffer("# c\r1\r\r2\r", "cr.txt").line_of(1), 4u);
}

TEST(TextReader, StreamInputAndBlockSizeDoNotChangeResults) {
  std::string text = "\xEF\xBB\xBF# comment\r\nt,x,y\r\n";
  for (int i = 0; i < 200; ++i) {
    text += std::to_string(i) + ", " + std::to_string(i * 0.25) + " ,-1e-3 # c\r\n";
    if (i % 17 == 0) text += "\r\n# gap\r\n";
  }
  TextReadOptions options = column(std::string("x"));
  options.time_column = std::string("t");
  const auto reference = read_text_buffer(text, "mem", options);
  ASSERT_EQ(reference.values.size(), 200u);
  for (std::size_t block : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{7},
                            std::size_t{64}, std::size_t{1} << 20}) {
    std::istringstream in(text);
    options.block_bytes = block;
    const auto r = read_text_stream(in, "<stdin>", options);
    EXPECT_EQ(r.values, reference.values) << block;
    EXPECT_EQ(r.time_s, reference.time_s) << block;
    EXPECT_EQ(r.header, reference.header) << block;
    for (std::size_t i = 0; i < r.values.size(); i += 13) {
      EXPECT_EQ(r.line_of(i), reference.line_of(i)) << block;
    }
  }
}

TEST(TextReader, CrLfSplitAcrossBlocks) {
  // With 1-byte blocks the '\r' and the '\n' of every line end arrive separately.
  std::istringstream in("1\r\n2\r\n3\r\n");
  TextReadOptions options;
  options.block_bytes = 1;
  EXPECT_EQ(read_text_stream(in, "<stdin>", options).values, (std::vector<double>{1, 2, 3}));
}

TEST(TextReader, LeadingPlusAndExponents) {
  EXPECT_EQ(read_values("+1\n+.5\n1E3\n-2.5e-1\n+1.5e+2\n5.\n"),
            (std::vector<double>{1.0, 0.5, 1000.0, -0.25, 150.0, 5.0}));
}

TEST(TextReader, ToleratesNonFiniteValuesInUnselectedColumns) {
  const auto r = read_text_buffer("1,nan\n2,inf\n", "dead.csv", column(std::size_t{0}));
  EXPECT_EQ(r.values, (std::vector<double>{1.0, 2.0}));
}

// --- exact parsing -------------------------------------------------------------------------------

TEST(TextReader, ParsesExactlyLikeStrtod) {
  std::vector<std::string> cells = {"0.1",
                                    "1e-300",
                                    "123456789.123456789",
                                    "5e-324",
                                    "4.9406564584124654e-324",
                                    "2.2250738585072011e-308",
                                    "1.7976931348623157e308",
                                    "-0.0",
                                    "0.30000000000000004",
                                    "9007199254740993",
                                    "2.4703282292062328e-324",
                                    "1.00000000000000011102230246251565404236316680908203125",
                                    "3.141592653589793238462643383279502884197"};
  std::mt19937_64 rng(20240521);
  std::uniform_int_distribution<std::uint64_t> bits;
  for (int i = 0; i < 2000; ++i) {
    const double value = std::bit_cast<double>(bits(rng));
    if (!std::isfinite(value)) continue;
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    cells.emplace_back(buffer);
    std::snprintf(buffer, sizeof buffer, "%.6e", value);  // not round-trippable: rounding matters
    cells.emplace_back(buffer);
  }
  std::string text;
  for (const auto& cell : cells) text += cell + "\n";

  TempDir dir;
  const auto path = dir.write("exact.txt", text);
  const auto r = read_text_file(path);
  ASSERT_EQ(r.values.size(), cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const double expected = std::strtod(cells[i].c_str(), nullptr);
    EXPECT_TRUE(same_bits(r.values[i], expected))
        << cells[i] << ": " << r.values[i] << " vs strtod " << expected;
  }
}

TEST(TextReader, ParseNumber) {
  EXPECT_EQ(parse_number("0.1"), 0.1);
  EXPECT_EQ(parse_number("+2"), 2.0);
  EXPECT_FALSE(parse_number("+-2"));
  EXPECT_FALSE(parse_number("1.0abc"));
  EXPECT_FALSE(parse_number(" 1"));
  EXPECT_FALSE(parse_number(""));
  EXPECT_FALSE(parse_number("0x10"));
  EXPECT_FALSE(parse_number("1,5"));
  EXPECT_TRUE(std::isnan(*parse_number("nan")));
  EXPECT_TRUE(std::isinf(*parse_number("1e999")));
}

// --- time column ---------------------------------------------------------------------------------

TEST(TextReader, TimeColumnInSeconds) {
  TextReadOptions options;
  options.time_column = std::size_t{0};  // the value column is then the other one of two
  const auto r = read_text_buffer("t,x\n10.0,1\n10.5,2\n11.0,3\n", "t.csv", options);
  EXPECT_EQ(r.value_column, 1u);
  EXPECT_EQ(r.values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(r.time_s, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(r.time_origin, "10.0");
  EXPECT_EQ(r.time_unit.name, "s");
}

TEST(TextReader, IntegerNanosecondTimestampsKeepFullResolution) {
  // ROS-style stamps at 200 Hz with 1 ns jitter; as doubles, 1.6e18 has a 256 ns resolution.
  const std::int64_t start = 1'600'000'000'123'456'789;
  std::string text = "stamp_ns gyro\n";
  std::vector<std::int64_t> stamps;
  for (std::int64_t k = 0; k < 50; ++k) {
    stamps.push_back(start + k * 5'000'000 + (k % 2));
    text += std::to_string(stamps.back()) + " " + std::to_string(k) + "\n";
  }
  TextReadOptions options;
  options.time_column = std::string("stamp_ns");
  const auto r = read_text_buffer(text, "ros.txt", options);
  EXPECT_EQ(r.time_unit.name, "ns");
  ASSERT_EQ(r.time_s.size(), 50u);
  for (std::size_t k = 0; k < 50; ++k) {
    // Correctly rounded: the integer nanoseconds divided by exactly 1e9.
    const double exact_s = static_cast<double>(stamps[k] - start) / 1e9;
    EXPECT_EQ(r.time_s[k], exact_s) << k;
  }
  EXPECT_EQ(r.time_s[1] - r.time_s[0], 0.005000001);
}

TEST(TextReader, EpochSecondsWithNanosecondDecimals) {
  TextReadOptions options;
  options.time_column = std::size_t{0};
  const auto r = read_text_buffer("1700000000.000000001,1\n1700000000.005000002,2\n", "e.csv", options);
  EXPECT_EQ(r.time_unit.name, "s");
  EXPECT_NEAR(r.time_s[1], 0.005000001, 1e-15);
}

TEST(TextReader, ExplicitTimeUnit) {
  TextReadOptions options;
  options.time_column = std::size_t{0};
  options.time_unit = parse_unit("ms");
  const auto r = read_text_buffer("1000,1\n1005,2\n", "ms.csv", options);
  EXPECT_EQ(r.time_s, (std::vector<double>{0.0, 0.005}));
  options.time_unit = parse_unit("deg");
  expect_input_error([&] { read_text_buffer("1000,1\n1005,2\n", "ms.csv", options); },
                     {"ms.csv:", "'deg'", "not a unit of time"});
}

// --- errors --------------------------------------------------------------------------------------

TEST(TextReaderErrors, EmptyFile) {
  TempDir dir;
  const auto path = dir.write("empty.csv", "");
  expect_input_error([&] { read_text_file(path); }, {path.string() + ":", "empty file"});
}

TEST(TextReaderErrors, OnlyCommentsAndBlankLines) {
  expect_input_error([] { read_text_buffer("# a\n\n   \n# b\n", "c.csv"); },
                     {"c.csv:", "no data lines"});
}

TEST(TextReaderErrors, HeaderOnly) {
  expect_input_error([] { read_text_buffer("# x\ntime,gyro\n", "h.csv", column(std::size_t{1})); },
                     {"h.csv:2:", "header line but no data rows"});
}

TEST(TextReaderErrors, RaggedRows) {
  expect_input_error([] { read_text_buffer("1,2,3\n4,5\n", "r.csv", column(std::size_t{0})); },
                     {"r.csv:2:", "2 fields", "first data row (line 1) has 3", "comma"});
  expect_input_error(
      [] { read_text_buffer("a b\n1 2\n3 4 5 6\n", "r.txt", column(std::size_t{0})); },
      {"r.txt:3:", "4 fields", "header (line 1) has 2", "whitespace"});
}

TEST(TextReaderErrors, NonNumericCell) {
  const std::string text = "t,gx,gy\n0,1,2\n1,abc,3\n";
  expect_input_error([&] { read_text_buffer(text, "n.csv", column(std::size_t{2})); },
                     {"n.csv:3:", "column 1 \"gx\"", "'abc'", "is not a number"});
  // A decimal comma in a semicolon file gets a hint.
  expect_input_error([] { read_text_buffer("1;2\n1,5;3\n", "d.csv", column(std::size_t{0})); },
                     {"d.csv:2:", "column 0", "'1,5'", "'.' as the decimal point (not ',')"});
}

TEST(TextReaderErrors, LongCellsAreTruncatedInMessages) {
  const std::string junk(200, 'z');
  const std::string message =
      expect_input_error([&] { read_text_buffer("1\n" + junk + "\n", "long.txt"); },
                         {"long.txt:2:", "'" + std::string(40, 'z') + "...'"});
  EXPECT_EQ(message.find(std::string(41, 'z')), std::string::npos);
}

TEST(TextReaderErrors, BinaryBytesAreEscapedInMessages) {
  expect_input_error([] { read_text_buffer(std::string("1\n2\x01\xff\n", 6), "bin.txt"); },
                     {"bin.txt:2:", "'2\\x01\\xff'"});
}

TEST(TextReaderErrors, EmptyCell) {
  expect_input_error([] { read_text_buffer("1,2,3\n4,,6\n", "e.csv", column(std::size_t{0})); },
                     {"e.csv:2:", "column 1", "empty cell"});
}

TEST(TextReaderErrors, FirstLineMixingNumbersAndText) {
  expect_input_error([] { read_text_buffer("time,1,2\n0,1,2\n", "m.csv", column(std::size_t{1})); },
                     {"m.csv:1:", "'time'", "header only when none of its fields is a number"});
}

TEST(TextReaderErrors, SecondHeaderLine) {
  expect_input_error([] { read_text_buffer("t,x\nsec,deg\n0,1\n", "h2.csv", column(std::size_t{1})); },
                     {"h2.csv:2:", "'sec'", "only one header line"});
}

TEST(TextReaderErrors, NanAndInfNameSampleAndLine) {
  expect_input_error([] { read_text_buffer("# c\n1\n2\nNaN\n", "nan.txt"); },
                     {"nan.txt:4:", "sample 2", "'NaN'", "NaN or Inf", "never skips"});
  expect_input_error([] { read_text_buffer("1\n-inf\n", "inf.txt"); },
                     {"inf.txt:2:", "sample 1", "NaN or Inf"});
  expect_input_error([] { read_text_buffer("1\n1e999\n", "big.txt"); },
                     {"big.txt:2:", "sample 1", "outside the range of a double"});
  TextReadOptions options;
  options.time_column = std::size_t{0};
  expect_input_error([&] { read_text_buffer("0,1\nnan,2\n", "tn.csv", options); },
                     {"tn.csv:2:", "sample 1", "column 0", "NaN or Inf"});
}

TEST(TextReaderErrors, TimeSpanOverflow) {
  TextReadOptions options;
  options.time_column = std::size_t{0};
  expect_input_error([&] { read_text_buffer("-1e308,1\n1e308,2\n", "span.csv", options); },
                     {"span.csv:2:", "sample 1", "column 0", "overflows"});
}

TEST(TextReaderErrors, AmbiguousColumnsListNamesAndSayPassColumn) {
  expect_input_error([] { read_text_buffer("t,gx,gy\n0,1,2\n", "a.csv"); },
                     {"a.csv:1:", "3 columns", "0 \"t\"", "1 \"gx\"", "2 \"gy\"", "pass --column"});
  expect_input_error([] { read_text_buffer("0 1 2 3\n", "b.txt"); },
                     {"b.txt:1:", "4 columns", "0..3", "no header line", "pass --column"});
}

TEST(TextReaderErrors, ColumnThatDoesNotExist) {
  expect_input_error([] { read_text_buffer("t,gx\n0,1\n", "x.csv", column(std::size_t{5})); },
                     {"x.csv:1:", "column 5", "does not exist", "2 columns", "\"gx\""});
  expect_input_error([] { read_text_buffer("t,gx\n0,1\n", "x.csv", column(std::string("gz"))); },
                     {"x.csv:1:", "\"gz\"", "does not exist", "0 \"t\"", "1 \"gx\""});
  expect_input_error([] { read_text_buffer("0,1\n", "y.csv", column(std::string("gx"))); },
                     {"y.csv:1:", "\"gx\"", "no header line", "0-based index"});
  expect_input_error(
      [] { read_text_buffer("gx,gx\n0,1\n", "dup.csv", column(std::string("gx"))); },
      {"dup.csv:1:", "more than one column"});
  TextReadOptions options = column(std::size_t{0});
  options.time_column = std::size_t{9};
  expect_input_error([&] { read_text_buffer("0,1\n", "t.csv", options); },
                     {"t.csv:1:", "column 9", "--time-column", "does not exist"});
}

TEST(TextReaderErrors, TimeAndValueColumnTheSame) {
  TextReadOptions options = column(std::size_t{1});
  options.time_column = std::size_t{1};
  expect_input_error([&] { read_text_buffer("0,1\n", "s.csv", options); },
                     {"s.csv:1:", "both column 1"});
  TextReadOptions only_time;
  only_time.time_column = std::size_t{0};
  expect_input_error([&] { read_text_buffer("0\n1\n", "o.csv", only_time); },
                     {"o.csv:1:", "only column is the time column"});
}

TEST(TextReaderErrors, Utf16) {
  expect_input_error([] { read_text_buffer(std::string("\xFF\xFE" "1\0\n\0", 6), "u16.txt"); },
                     {"u16.txt:1:", "UTF-16"});
}

TEST(TextReaderErrors, MissingFileAndDirectory) {
  TempDir dir;
  const auto missing = dir.path() / "nope.csv";
  expect_input_error([&] { read_text_file(missing); }, {missing.string(), "cannot open"});
  expect_input_error([&] { read_text_file(dir.path()); }, {"is a directory"});
}

TEST(TextReader, LineLongerThanTheBlock) {
  std::string row;
  for (int i = 0; i < 300; ++i) row += std::to_string(i) + ",";
  row += "300\n";
  std::istringstream in(row + row);
  TextReadOptions options = column(std::size_t{300});
  options.block_bytes = 16;
  const auto r = read_text_stream(in, "<stdin>", options);
  EXPECT_EQ(r.values, (std::vector<double>{300.0, 300.0}));
}

TEST(LineMap, RunsAndLookup) {
  LineMap map;
  EXPECT_EQ(map.line_of(0), 0u);
  map.add(0, 3);
  map.add(1, 4);
  map.add(2, 5);
  map.add(3, 9);
  map.add(4, 10);
  EXPECT_EQ(map.run_count(), 2u);
  EXPECT_EQ(map.line_of(0), 3u);
  EXPECT_EQ(map.line_of(2), 5u);
  EXPECT_EQ(map.line_of(3), 9u);
  EXPECT_EQ(map.line_of(4), 10u);
}

}  // namespace
}  // namespace imunoise::io
