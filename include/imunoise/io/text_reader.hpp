#pragma once
// Reading numeric columns from text files (CSV, TSV, space-separated, semicolon-separated).
//
// Format accepted (interface.md, "Command line"):
//  - lines end in LF, CRLF or CR; a UTF-8 byte-order mark at the start is skipped;
//  - '#' starts a comment, on a line of its own or after data; blank lines are skipped;
//  - the separator is detected on the first non-comment line: tab if it has tabs and either no
//    spaces or a tab-separated field with a space inside (e.g. the name "gyro x"); else ';' if it
//    has one; else ',' if it has one; else runs of blanks (spaces and tabs). Blanks around
//    fields are ignored; a field may be wrapped in double quotes (no separators inside quotes);
//  - the first non-comment line is a header when any of its fields is not a number; only one
//    header line is allowed. Every later line is a data row with the same number of fields;
//  - every cell of a data row must be a number (C locale, '.' decimal point, optional leading
//    '+' or '-', optional exponent), parsed exactly (correctly rounded, same bits as strtod).
//    The selected value and time columns must be finite; NaN or Inf elsewhere is tolerated so
//    that a dead channel does not block reading a good one.
// Column numbers are 0-based everywhere: in selectors (`--column 0` is the first column) and
// in messages. Line numbers in messages are 1-based, as in editors.
//
// Every problem is an InputError whose message starts with "<source>:<line>:" (or "<source>:"
// when no line applies), names the column and quotes the offending text (at most 40
// characters), and ends with "fix: ...". Nothing is skipped silently.
//
// Speed: a regular file is memory-mapped and parsed in place (no copy; the page faults that read
// it happen in the parsing threads, overlapped with parsing, and the pages already parsed are
// dropped from the mapping so that resident memory does not grow with the file); pipes and
// streams are read in blocks (8 MiB by default). Numbers are converted by fast_float or an exact
// fast path for decimals of at most 19 digits. Once the first data row has fixed the layout, the
// complete lines are cut at line ends into chunks of 1 MiB (at most block_bytes) that a pool
// of threads, started once per read, parses side by side with a row parser that only knows
// plain rows (numbers, separators, blanks around them): it converts the value column (and the
// time column) and only checks that the other cells are numbers; the calling thread takes the
// chunks in file order (at most 32 parsed ahead, so memory is the output vectors plus a few
// chunks' rows). Any line the row parser does not take (comment, blank, quote, NaN, ragged,
// error) goes to the line-by-line parser with the exact line number and row index, so values
// and messages are the same as when reading line by line (tested). Measured in
// bench/bench_text_reader.cpp and docs/performance.md.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "imunoise/units.hpp"

namespace imunoise::io {

/// A column chosen by 0-based index or by header name.
using ColumnSelector = std::variant<std::size_t, std::string>;

/// Parses the text of `--column N|NAME`: all digits -> 0-based index, anything else -> header
/// name (a header whose name is all digits can therefore only be chosen by index). Surrounding
/// spaces are ignored. Throws InputError for empty text or an index that does not fit.
ColumnSelector parse_column_selector(std::string_view text);

/// "column 2" or "column \"gyro_x\"", for messages.
std::string describe_column_selector(const ColumnSelector& selector);

/// Parses one cell as the reader does: C locale, optional leading '+' or '-', '.' decimal
/// point, optional exponent, the whole text must be the number (no spaces). Correctly rounded
/// (bit-identical to strtod). Returns nullopt for anything else; "nan", "inf" and overflowing
/// values such as 1e999 are returned as non-finite doubles for the caller to judge.
std::optional<double> parse_number(std::string_view text);

enum class Separator { comma, tab, semicolon, whitespace };

/// "comma", "tab", "semicolon", "whitespace".
std::string_view separator_name(Separator separator);

/// The fields of one header or data line as the reader splits them: the separator detected
/// as for a file's first line, each field trimmed and unquoted.
std::vector<std::string> split_fields(std::string_view line);

/// Maps sample indices to 1-based line numbers without storing one number per sample: it keeps
/// one entry per run of consecutive data lines (comments and blank lines start a new run).
class LineMap {
 public:
  /// Records that sample `sample` is on line `line`; samples must be added in order.
  void add(std::size_t sample, std::size_t line);
  /// Line of a sample that was added (or of a later one in the same run). 0 if none was added.
  [[nodiscard]] std::size_t line_of(std::size_t sample) const;
  [[nodiscard]] std::size_t run_count() const { return runs_.size(); }

 private:
  struct Run {
    std::size_t first_sample;
    std::size_t first_line;
  };
  std::vector<Run> runs_;
};

struct TextReadOptions {
  /// Column of the values. Empty: the only column; or, when a time column is chosen and the
  /// file has exactly two columns, the other one. Otherwise leaving it empty is an error.
  std::optional<ColumnSelector> column;
  /// Optional column of timestamps, returned as seconds since the first sample.
  std::optional<ColumnSelector> time_column;
  /// Unit of the time column (a time unit: s, ms, us, ns). Empty: seconds, unless the values
  /// look like integer nanoseconds (see looks_like_nanoseconds in timestamps.hpp).
  std::optional<Unit> time_unit;
  /// Size of the blocks read from a stream or a file that cannot be mapped (bytes, >= 1); the
  /// parallel parser's chunks are at most this size. Tuning only: results do not depend on it.
  std::size_t block_bytes = std::size_t{1} << 23;
  /// Threads that parse the rows of a block side by side (0: all cores). Tuning only: values,
  /// line numbers and error messages do not depend on it.
  unsigned threads = 0;
  /// Parse plain rows (numbers and separators only) with the bulk row parser, falling back to
  /// the line-by-line parser for any other line. Tuning and testing only: results and error
  /// messages are identical either way; false gives the plain single-threaded line-by-line read.
  bool bulk_rows = true;
};

/// The columns read from a text file, as written (no unit conversion of values).
struct TextColumns {
  std::string source;                ///< file name used in messages
  std::vector<std::string> header;   ///< column names; empty when there is no header line
  std::size_t header_line = 0;       ///< 1-based line of the header; 0 when none
  std::size_t first_data_line = 0;   ///< 1-based line of the first data row
  Separator separator = Separator::whitespace;
  std::size_t column_count = 0;      ///< fields per data row
  std::size_t value_column = 0;      ///< 0-based column read into `values`
  std::optional<std::size_t> time_column;  ///< 0-based column read into `time_s`, if any
  std::vector<double> values;        ///< one per data row, in file order, finite
  /// Time of each row in seconds since the first row (time_s[0] == 0); empty without a time
  /// column. Differences are exact to 1 ns for integer-nanosecond stamps (timestamps.hpp).
  std::vector<double> time_s;
  std::string time_origin;           ///< the first timestamp cell exactly as written
  Unit time_unit{"s", Quantity::time, 1.0};  ///< unit the time column was read in (given or detected)
  LineMap lines;                     ///< line of each sample, for messages

  /// 1-based line of sample `index`.
  [[nodiscard]] std::size_t line_of(std::size_t index) const { return lines.line_of(index); }
};

/// Reads a text file. Throws InputError (cannot open, empty, malformed, ...; see above).
TextColumns read_text_file(const std::filesystem::path& path, const TextReadOptions& options = {});

/// Reads text from a stream (the CLI passes std::cin for "-"); `source` names it in messages.
TextColumns read_text_stream(std::istream& in, std::string_view source,
                             const TextReadOptions& options = {});

/// Reads text held in memory; `source` names it in messages.
TextColumns read_text_buffer(std::string_view text, std::string_view source,
                             const TextReadOptions& options = {});

}  // namespace imunoise::io
