#include "imunoise/io/binary_reader.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <istream>
#include <system_error>

#include "imunoise/error.hpp"
#include "mapped_file.hpp"

namespace imunoise::io {
namespace {

constexpr std::size_t max_channels = 65536;

constexpr const char* valid_formats =
    "f32, f64, i16 or i32, optionally followed by :le or :be (default :le), e.g. f64:be";

template <class Unsigned>
Unsigned byte_swap(Unsigned value) {
  Unsigned swapped = 0;
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i) {
    swapped = static_cast<Unsigned>((swapped << 8) | (value & 0xffu));
    value = static_cast<Unsigned>(value >> 8);
  }
  return swapped;
}

// Reads one sample stored as `Unsigned` bits in `order` and reinterprets it as `Value`.
template <class Value, class Unsigned>
double load(const unsigned char* bytes, ByteOrder order) {
  static_assert(sizeof(Value) == sizeof(Unsigned));
  Unsigned bits = 0;
  std::memcpy(&bits, bytes, sizeof bits);
  const bool native = (order == ByteOrder::little) == (std::endian::native == std::endian::little);
  if (!native) bits = byte_swap(bits);
  return static_cast<double>(std::bit_cast<Value>(bits));
}

double load_sample(const unsigned char* bytes, const BinaryFormat& format) {
  switch (format.type) {
    case SampleType::f32: return load<float, std::uint32_t>(bytes, format.order);
    case SampleType::f64: return load<double, std::uint64_t>(bytes, format.order);
    case SampleType::i16: return load<std::int16_t, std::uint16_t>(bytes, format.order);
    case SampleType::i32: return load<std::int32_t, std::uint32_t>(bytes, format.order);
  }
  return 0.0;
}

std::string record_layout(const BinaryReadOptions& options) {
  return std::to_string(options.channels) + " channel(s) x " +
         binary_format_name(options.format) + ", " +
         std::to_string(options.format.sample_bytes() * options.channels) + " bytes per record";
}

void check_options(const BinaryReadOptions& options, std::string_view source) {
  const std::string where = std::string(source) + ": ";
  if (options.channels == 0 || options.channels > max_channels) {
    throw InputError(where + "--channels " + std::to_string(options.channels) +
                     " is out of range; fix: pass the number of interleaved channels, 1.." +
                     std::to_string(max_channels));
  }
  if (options.column >= options.channels) {
    throw InputError(where + "--column " + std::to_string(options.column) +
                     " does not exist: records have " + std::to_string(options.channels) +
                     " channel(s), columns 0.." + std::to_string(options.channels - 1) +
                     "; fix: pass a 0-based --column below --channels");
  }
  if (!std::isfinite(options.scale) || options.scale == 0.0) {
    throw InputError(where + "scale factor " + std::to_string(options.scale) +
                     " is not a finite non-zero number; fix: pass the size of one count in the "
                     "output unit");
  }
}

[[noreturn]] void throw_truncated(std::string_view source, std::size_t trailing_bytes,
                                  std::size_t complete_records, const BinaryReadOptions& options) {
  throw InputError(std::string(source) + ": truncated: " + std::to_string(trailing_bytes) +
                   " trailing byte(s) after " + std::to_string(complete_records) +
                   " complete record(s); record " + std::to_string(complete_records) +
                   " (0-based) is incomplete (" + record_layout(options) +
                   "); fix: check --binary and --channels, or cut the file to a whole number "
                   "of records");
}

[[noreturn]] void throw_empty(std::string_view source) {
  throw InputError(std::string(source) + ": empty input (no bytes); fix: check that the right "
                   "file was given");
}

}  // namespace

std::size_t BinaryFormat::sample_bytes() const {
  switch (type) {
    case SampleType::f32: return 4;
    case SampleType::f64: return 8;
    case SampleType::i16: return 2;
    case SampleType::i32: return 4;
  }
  return 0;
}

BinaryFormat parse_binary_format(std::string_view text) {
  BinaryFormat format;
  const std::size_t colon = text.find(':');
  const std::string_view type = text.substr(0, colon);
  if (type == "f32") {
    format.type = SampleType::f32;
  } else if (type == "f64") {
    format.type = SampleType::f64;
  } else if (type == "i16") {
    format.type = SampleType::i16;
  } else if (type == "i32") {
    format.type = SampleType::i32;
  } else {
    throw InputError("unknown binary format '" + std::string(text) + "'; fix: pass " +
                     valid_formats);
  }
  if (colon != std::string_view::npos) {
    const std::string_view order = text.substr(colon + 1);
    if (order == "le") {
      format.order = ByteOrder::little;
    } else if (order == "be") {
      format.order = ByteOrder::big;
    } else {
      throw InputError("unknown byte order '" + std::string(order) + "' in binary format '" +
                       std::string(text) + "'; fix: pass " + valid_formats);
    }
  }
  return format;
}

std::string binary_format_name(const BinaryFormat& format) {
  std::string name;
  switch (format.type) {
    case SampleType::f32: name = "f32"; break;
    case SampleType::f64: name = "f64"; break;
    case SampleType::i16: name = "i16"; break;
    case SampleType::i32: name = "i32"; break;
  }
  return name + (format.order == ByteOrder::little ? ":le" : ":be");
}

std::optional<BinaryFormat> binary_format_from_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* known : {".f32", ".f64", ".i16", ".i32"}) {
    if (extension == known) return parse_binary_format(extension.substr(1));
  }
  return std::nullopt;
}

BinaryReader::BinaryReader(const std::filesystem::path& path, const BinaryReadOptions& options)
    : source_(path.string()), options_(options) {
  check_options(options_, source_);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(source_ + ": is a directory; fix: give the path of a binary file");
  }
  file_.reset(std::fopen(source_.c_str(), "rb"));
  if (!file_) {
    throw InputError(source_ + ": cannot open (" + std::strerror(errno) +
                     "); fix: check the path and the permissions");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) {
    throw InputError(source_ + ": cannot determine the file size (" + ec.message() +
                     "); fix: give a regular file, or read it from standard input");
  }
  if (size == 0) throw_empty(source_);
  const std::size_t trailing = static_cast<std::size_t>(size % record_bytes());
  if (trailing != 0) {
    throw_truncated(source_, trailing, static_cast<std::size_t>(size / record_bytes()), options_);
  }
  record_count_ = static_cast<std::size_t>(size / record_bytes());
  try {
    map_ = std::make_unique<MappedFile>(path);
  } catch (const InputError&) {
    map_.reset();  // not mappable: read in chunks below
  }
  // Chunks go straight into our buffer; stdio's own buffer would only add a copy.
  std::setvbuf(file_.get(), nullptr, _IONBF, 0);
}

BinaryReader::~BinaryReader() = default;

BinaryReader::BinaryReader(std::istream& in, std::string_view source,
                           const BinaryReadOptions& options)
    : source_(source), options_(options), stream_(&in) {
  check_options(options_, source_);
}

std::size_t BinaryReader::record_bytes() const {
  return options_.format.sample_bytes() * options_.channels;
}

std::size_t BinaryReader::read_bytes(unsigned char* destination, std::size_t count) {
  std::size_t total = 0;
  while (total < count) {
    std::size_t got = 0;
    if (file_) {
      got = std::fread(destination + total, 1, count - total, file_.get());
      if (got == 0 && std::ferror(file_.get())) {
        throw InputError(source_ + ": read error (" + std::strerror(errno) +
                         "); fix: check the file and the disk");
      }
    } else {
      stream_->read(reinterpret_cast<char*>(destination + total),
                    static_cast<std::streamsize>(count - total));
      if (stream_->bad()) throw InputError(source_ + ": read error; fix: check the input stream");
      got = static_cast<std::size_t>(stream_->gcount());
    }
    if (got == 0) break;
    total += got;
  }
  return total;
}

namespace {

// One channel of `records` records into doubles times `scale`; the format switch is outside
// the loop so that each loop is a plain load-convert-multiply the compiler vectorises.
template <class Value, class Unsigned>
void convert(const unsigned char* bytes, std::size_t stride, std::size_t records, ByteOrder order,
             double scale, double* out) {
  const bool native = (order == ByteOrder::little) == (std::endian::native == std::endian::little);
  if (native && stride == sizeof(Value)) {  // one channel in the machine's order: a plain loop
    for (std::size_t r = 0; r < records; ++r) {
      Value v;
      std::memcpy(&v, bytes + r * sizeof(Value), sizeof v);
      out[r] = static_cast<double>(v) * scale;
    }
    return;
  }
  for (std::size_t r = 0; r < records; ++r) out[r] = load<Value, Unsigned>(bytes + r * stride, order) * scale;
}

}  // namespace

void BinaryReader::decode(const unsigned char* bytes, std::size_t records, double* out) const {
  const std::size_t stride = record_bytes();
  const std::size_t offset = options_.column * options_.format.sample_bytes();
  const unsigned char* first = bytes + offset;
  const ByteOrder order = options_.format.order;
  switch (options_.format.type) {
    case SampleType::f32: convert<float, std::uint32_t>(first, stride, records, order, options_.scale, out); break;
    case SampleType::f64: convert<double, std::uint64_t>(first, stride, records, order, options_.scale, out); break;
    case SampleType::i16: convert<std::int16_t, std::uint16_t>(first, stride, records, order, options_.scale, out); break;
    case SampleType::i32: convert<std::int32_t, std::uint32_t>(first, stride, records, order, options_.scale, out); break;
  }
  // NaN and Inf: one check over the block (NaN * scale stays NaN, Inf stays Inf).
  bool finite = true;
  for (std::size_t r = 0; r < records; ++r) finite &= std::isfinite(out[r]);
  if (finite) return;
  for (std::size_t r = 0; r < records; ++r) {
    if (std::isfinite(out[r])) continue;
    const double raw = load_sample(first + r * stride, options_.format);
    const std::size_t record = next_record_ + r;
    const std::string what = std::isfinite(raw)
                                 ? " overflows when multiplied by the scale factor"
                                 : " is NaN or Inf";
    throw InputError(source_ + ": record " + std::to_string(record) + " (sample " +
                     std::to_string(record) + ", byte offset " +
                     std::to_string(record * stride + offset) + "), column " +
                     std::to_string(options_.column) + what +
                     "; fix: repair or cut the record there (imunoise never skips samples), "
                     "or check --binary and --channels");
  }
}

void BinaryReader::seek(std::size_t record) {
  if (!file_ || !record_count_) {
    throw InputError(source_ + ": cannot seek in a stream; fix: give a file path");
  }
  if (record > *record_count_) {
    throw InputError(source_ + ": record " + std::to_string(record) + " is past the end (" +
                     std::to_string(*record_count_) + " records)");
  }
  const auto offset = static_cast<off_t>(record * record_bytes());
  if (::fseeko(file_.get(), offset, SEEK_SET) != 0) {
    throw InputError(source_ + ": cannot seek to record " + std::to_string(record) + " (" +
                     std::strerror(errno) + "); fix: give a regular file");
  }
  next_record_ = record;
  at_end_ = record == *record_count_;
}

std::size_t BinaryReader::read(std::span<double> out) {
  if (out.empty() || at_end_) return 0;
  const std::size_t stride = record_bytes();
  std::size_t wanted = out.size();
  if (record_count_) wanted = std::min(wanted, *record_count_ - next_record_);
  if (map_ && map_->bytes().size() == *record_count_ * stride) {
    // Straight from the mapping, its pages mapped ahead in bulk; the pages behind are dropped
    // so that memory stays bounded.
    map_->populate_ahead(next_record_ * stride);
    decode(map_->bytes().data() + next_record_ * stride, wanted, out.data());
    next_record_ += wanted;
    map_->release_before(next_record_ * stride);
    if (next_record_ == *record_count_) at_end_ = true;
    return wanted;
  }
  const std::size_t chunk_records = std::max<std::size_t>(1, options_.chunk_bytes / stride);
  std::size_t produced = 0;
  while (produced < wanted) {
    const std::size_t records = std::min(wanted - produced, chunk_records);
    buffer_.resize(records * stride);
    const std::size_t got = read_bytes(buffer_.data(), records * stride);
    const std::size_t complete = got / stride;
    decode(buffer_.data(), complete, out.data() + produced);
    produced += complete;
    next_record_ += complete;
    if (got < records * stride) {  // end of input
      if (got % stride != 0) throw_truncated(source_, got % stride, next_record_, options_);
      if (next_record_ == 0) throw_empty(source_);
      if (record_count_ && next_record_ != *record_count_) {
        throw InputError(source_ + ": the file ended after " + std::to_string(next_record_) +
                         " of " + std::to_string(*record_count_) +
                         " records (was it changed while being read?); fix: read it again");
      }
      at_end_ = true;
      break;
    }
  }
  if (record_count_ && next_record_ == *record_count_) at_end_ = true;
  return produced;
}

namespace {
std::vector<double> read_all(BinaryReader& reader) {
  std::vector<double> values;
  if (reader.record_count()) {  // a file: its length is known, so read straight into place
    values.resize(*reader.record_count());
    values.resize(reader.read(values));
    return values;
  }
  std::vector<double> chunk(std::size_t{1} << 16);
  while (const std::size_t n = reader.read(chunk)) {
    values.insert(values.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return values;
}
}  // namespace

std::vector<double> read_binary_file(const std::filesystem::path& path,
                                     const BinaryReadOptions& options) {
  BinaryReader reader(path, options);
  return read_all(reader);
}

std::vector<double> read_binary_stream(std::istream& in, std::string_view source,
                                       const BinaryReadOptions& options) {
  BinaryReader reader(in, source, options);
  return read_all(reader);
}

}  // namespace imunoise::io
