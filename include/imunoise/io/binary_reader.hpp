#pragma once
// Reading raw binary samples: records of C interleaved channels, each channel one f32, f64, i16
// or i32 in little- or big-endian byte order, no header. One channel is read, optionally
// scaled (for integer ADC counts), and converted to double exactly (every f32, i16 and i32
// value is a double; the only rounding is the one multiplication by `scale` when it is not 1).
//
// Files are mapped and decoded straight from the mapping (no copy through read(); the pages
// already decoded are dropped from the process, so resident memory stays bounded); streams,
// and files that cannot be mapped, are read in chunks. read_binary_file is the
// read-everything convenience.
//
// Problems are InputError naming the source and the record (0-based) and saying the fix:
// empty input, a length that is not a whole number of records ("truncated: N trailing
// bytes ..."), a column >= channels, a NaN or Inf in the selected channel.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::io {

class MappedFile;

enum class SampleType { f32, f64, i16, i32 };
enum class ByteOrder { little, big };

struct BinaryFormat {
  SampleType type = SampleType::f64;
  ByteOrder order = ByteOrder::little;

  /// Bytes of one sample of one channel: 4, 8, 2 or 4.
  [[nodiscard]] std::size_t sample_bytes() const;
  friend bool operator==(const BinaryFormat&, const BinaryFormat&) = default;
};

/// Parses "f32", "f64", "i16" or "i32", optionally followed by ":le" or ":be" (default le), as
/// in `--binary f64:be`. Throws InputError listing the valid forms.
BinaryFormat parse_binary_format(std::string_view text);

/// "f64:le" etc.; parse_binary_format(binary_format_name(f)) == f.
std::string binary_format_name(const BinaryFormat& format);

/// The format implied by a file extension: .f32 .f64 .i16 .i32 (any case; little-endian).
/// nullopt for anything else, including .bin and .raw, whose format must be given explicitly.
std::optional<BinaryFormat> binary_format_from_extension(const std::filesystem::path& path);

struct BinaryReadOptions {
  BinaryFormat format;
  std::size_t channels = 1;   ///< interleaved channels per record, 1..65536
  std::size_t column = 0;     ///< 0-based channel to read, < channels
  double scale = 1.0;         ///< value = raw * scale (e.g. deg/s per ADC count); finite, != 0
  std::size_t chunk_bytes = std::size_t{1} << 20;  ///< read size; tuning only, >= 1
};

/// Streams one channel of a raw binary file or stream.
class BinaryReader {
 public:
  /// Opens a file and checks the options and that its length is a whole, non-zero number of
  /// records. Throws InputError otherwise.
  BinaryReader(const std::filesystem::path& path, const BinaryReadOptions& options);
  /// Reads from a stream (e.g. standard input) whose length is unknown: a trailing partial
  /// record or empty input is reported by the read() that reaches the end. `source` names the
  /// stream in messages. The stream must outlive the reader.
  BinaryReader(std::istream& in, std::string_view source, const BinaryReadOptions& options);
  ~BinaryReader();
  BinaryReader(const BinaryReader&) = delete;
  BinaryReader& operator=(const BinaryReader&) = delete;

  /// Fills `out` with the next samples of the selected channel; returns how many were written
  /// (< out.size() only at the end of input; 0 once everything has been read).
  /// Throws InputError for NaN or Inf (naming the record), truncation and empty input.
  std::size_t read(std::span<double> out);

  /// Files only: the next read() starts at record `record` (<= record_count()), so that each
  /// process of a parallel run reads its own slice with positioned reads. InputError for a
  /// stream or a record past the end.
  void seek(std::size_t record);

  /// Number of records in a file; nullopt for a stream.
  [[nodiscard]] std::optional<std::size_t> record_count() const { return record_count_; }
  /// Records delivered so far (the index of the next one).
  [[nodiscard]] std::size_t records_read() const { return next_record_; }
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const BinaryReadOptions& options() const { return options_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const noexcept { std::fclose(file); }
  };

  std::size_t record_bytes() const;
  std::size_t read_bytes(unsigned char* destination, std::size_t count);
  void decode(const unsigned char* bytes, std::size_t records, double* out) const;

  std::string source_;
  BinaryReadOptions options_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::istream* stream_ = nullptr;
  std::unique_ptr<MappedFile> map_;  ///< the whole file, when it could be mapped
  std::optional<std::size_t> record_count_;
  std::size_t next_record_ = 0;
  bool at_end_ = false;
  std::vector<unsigned char> buffer_;
};

/// Reads the whole selected channel of a file.
std::vector<double> read_binary_file(const std::filesystem::path& path,
                                     const BinaryReadOptions& options);

/// Reads the whole selected channel of a stream; `source` names it in messages.
std::vector<double> read_binary_stream(std::istream& in, std::string_view source,
                                       const BinaryReadOptions& options);

}  // namespace imunoise::io
