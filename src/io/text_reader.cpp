#include "imunoise/io/text_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <condition_variable>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <istream>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

#include <fast_float/fast_float.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "imunoise/error.hpp"
#include "imunoise/io/timestamps.hpp"
#include "../core/parallel.hpp"  // the library's fork-join helper

namespace imunoise::io {
namespace {

constexpr std::size_t excerpt_max_chars = 40;
constexpr std::size_t listed_columns_max = 16;

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::string_view trim(std::string_view text) {
  std::size_t first = 0;
  std::size_t last = text.size();
  while (first < last && is_blank(text[first])) ++first;
  while (last > first && is_blank(text[last - 1])) --last;
  return text.substr(first, last - first);
}

// Removes one pair of surrounding double quotes (spreadsheets quote header names).
std::string_view unquote(std::string_view field) {
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') {
    return trim(field.substr(1, field.size() - 2));
  }
  return field;
}

// The offending text for a message: quoted, at most 40 characters, bytes that are not
// printable ASCII shown as \xNN so that binary junk cannot garble a terminal.
std::string escaped(std::string_view text, char quote) {
  std::string out(1, quote);
  std::size_t shown = 0;
  for (char c : text) {
    if (shown == excerpt_max_chars) {
      out += "...";
      break;
    }
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      static constexpr char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[byte >> 4];
      out += hex[byte & 0xf];
    }
    ++shown;
  }
  return out + quote;
}

std::string excerpt(std::string_view text) { return escaped(text, '\''); }
std::string quoted_name(std::string_view name) { return escaped(name, '"'); }

// Whether a text with blanks inside is a name ("gyro x") rather than numbers aligned by spaces.
bool is_spaced_name(std::string_view field) {
  std::size_t start = 0;
  while (start < field.size()) {
    if (is_blank(field[start])) {
      ++start;
      continue;
    }
    std::size_t end = start;
    while (end < field.size() && !is_blank(field[end])) ++end;
    if (!parse_number(field.substr(start, end - start))) return true;
    start = end;
  }
  return false;
}

// A line with tabs is tab-separated when tabs are the only blanks in it, or when some
// tab-separated field is a name with a blank inside ("gyro x"); otherwise the tabs are
// alignment mixed with spaces, and runs of blanks separate the fields.
bool tabs_separate_fields(std::string_view line) {
  if (line.find(' ') == std::string_view::npos) return true;
  std::size_t start = 0;
  while (start <= line.size()) {
    const std::size_t end = std::min(line.find('\t', start), line.size());
    const std::string_view field = trim(line.substr(start, end - start));
    if (field.find(' ') != std::string_view::npos && is_spaced_name(field)) return true;
    start = end + 1;
  }
  return false;
}

// Priority tab > ';' > ',' > spaces: a tab or ';' is never part of a number, whereas ',' can be
// a decimal comma in files that then use ';' between fields.
Separator detect_separator(std::string_view line) {
  if (line.find('\t') != std::string_view::npos) {
    return tabs_separate_fields(line) ? Separator::tab : Separator::whitespace;
  }
  if (line.find(';') != std::string_view::npos) return Separator::semicolon;
  if (line.find(',') != std::string_view::npos) return Separator::comma;
  return Separator::whitespace;
}

char separator_char(Separator separator) {
  switch (separator) {
    case Separator::comma: return ',';
    case Separator::tab: return '\t';
    case Separator::semicolon: return ';';
    case Separator::whitespace: return ' ';
  }
  return ' ';
}

// Walks the fields of one trimmed, non-empty line. Fields come out trimmed and unquoted.
class FieldCursor {
 public:
  FieldCursor(std::string_view line, Separator separator)
      : line_(line), separator_(separator), sep_char_(separator_char(separator)) {}

  bool next(std::string_view& field) {
    if (done_) return false;
    if (separator_ == Separator::whitespace) return next_word(field);
    const std::size_t end = line_.find(sep_char_, pos_);
    if (end == std::string_view::npos) {
      field = unquote(trim(line_.substr(pos_)));
      done_ = true;
    } else {
      field = unquote(trim(line_.substr(pos_, end - pos_)));
      pos_ = end + 1;
    }
    return true;
  }

  /// Number of fields from the current position on (for messages about ragged rows).
  std::size_t count_rest() {
    std::size_t n = 0;
    std::string_view field;
    while (next(field)) ++n;
    return n;
  }

 private:
  bool next_word(std::string_view& field) {
    while (pos_ < line_.size() && is_blank(line_[pos_])) ++pos_;
    if (pos_ == line_.size()) {
      done_ = true;
      return false;
    }
    std::size_t end = pos_;
    while (end < line_.size() && !is_blank(line_[end])) ++end;
    field = unquote(line_.substr(pos_, end - pos_));
    pos_ = end;
    return true;
  }

  std::string_view line_;
  Separator separator_;
  char sep_char_;
  std::size_t pos_ = 0;
  bool done_ = false;
};

std::string non_finite_reason(std::string_view field) {
  // fast_float turns both "nan"/"inf" literals and overflowing decimals such as 1e999 into
  // non-finite values; the letters tell which one the user wrote.
  const bool literal = field.find_first_of("nNiI") != std::string_view::npos;
  return literal ? "is NaN or Inf" : "is outside the range of a double (magnitude > 1.8e308)";
}

enum class LineEnd { unknown, lf, cr };

// Splits a byte stream into lines (LF, CRLF or CR endings; the kind is decided by the first line
// end) and hands them to `on_line` without the terminator. Blocks arrive through process().
template <class OnLine>
class LineSplitter {
 public:
  explicit LineSplitter(OnLine& on_line) : on_line_(on_line) {}

  /// Hands out every complete line of data[0, size) and, at end of input, the unterminated
  /// last one. Returns the number of bytes consumed; the rest must be passed again, followed
  /// by more input.
  std::size_t process(const char* data, std::size_t size, bool at_end) {
    std::size_t pos = 0;
    while (pos < size) {
      if (line_end_ == LineEnd::unknown && !decide_line_end(data, pos, size, at_end)) break;
      if (line_end_ == LineEnd::lf && on_line_.bulk_ready()) {
        // Every complete line left in the block at once (the parser may split them up).
        const void* last = memrchr(data + pos, '\n', size - pos);
        if (last == nullptr) break;
        const auto end = static_cast<std::size_t>(static_cast<const char*>(last) - data) + 1;
        on_line_.bulk(data + pos, end - pos);
        pos = end;
        continue;
      }
      const char terminator = line_end_ == LineEnd::cr ? '\r' : '\n';
      const void* hit = std::memchr(data + pos, terminator, size - pos);
      if (hit == nullptr) break;
      const auto end = static_cast<std::size_t>(static_cast<const char*>(hit) - data);
      emit(std::string_view(data + pos, end - pos));
      pos = end + 1;
    }
    if (at_end && pos < size) {
      emit(std::string_view(data + pos, size - pos));
      pos = size;
    }
    return pos;
  }

 private:
  // Looks at the first '\r' or '\n' from pos. Returns false when that needs more input.
  bool decide_line_end(const char* data, std::size_t pos, std::size_t size, bool at_end) {
    const std::string_view rest(data + pos, size - pos);
    const std::size_t i = rest.find_first_of("\r\n");
    if (i == std::string_view::npos) return at_end;  // no line end yet: need more, or one line
    if (rest[i] == '\n') {
      line_end_ = LineEnd::lf;
    } else if (i + 1 < rest.size()) {
      line_end_ = rest[i + 1] == '\n' ? LineEnd::lf : LineEnd::cr;
    } else if (at_end) {
      line_end_ = LineEnd::lf;  // a final lone '\r': trimmed off as trailing blank
    } else {
      return false;
    }
    return true;
  }

  void emit(std::string_view line) {
    if (line_end_ != LineEnd::cr && !line.empty() && line.back() == '\r') line.remove_suffix(1);
    on_line_(line);
  }

  OnLine& on_line_;
  LineEnd line_end_ = LineEnd::unknown;
};

// Feeds `read(dst, capacity) -> bytes` (0 at end) through a LineSplitter in blocks.
template <class Read, class OnLine>
void split_blocks(Read&& read, std::size_t block_bytes, OnLine& on_line) {
  LineSplitter<OnLine> splitter(on_line);
  std::vector<char> buffer(std::max<std::size_t>(block_bytes, 1));
  std::size_t have = 0;
  bool at_end = false;
  while (!at_end) {
    if (have == buffer.size()) buffer.resize(buffer.size() * 2);  // one line longer than a block
    const std::size_t got = read(buffer.data() + have, buffer.size() - have);
    at_end = got == 0;
    have += got;
    const std::size_t used = splitter.process(buffer.data(), have, at_end);
    std::memmove(buffer.data(), buffer.data() + used, have - used);
    have -= used;
  }
}

// --- bulk row parser -----------------------------------------------------------------------------
// Plain rows only: cells that are numbers, separated as the first row was, blanks around them.
// Anything else is left to the line-by-line parser, so this parser never has to judge an error.

struct RowLayout {
  Separator separator;
  std::size_t columns;
  std::size_t value_column;
  std::optional<std::size_t> time_column;
};

struct PlainRows {
  std::vector<double> values;
  std::vector<SplitTime> times;
  std::string first_time;  ///< the first time cell as written
  std::size_t rows = 0;    ///< rows parsed = lines consumed
  void clear() {
    values.clear();
    times.clear();
    first_time.clear();
    rows = 0;
  }
};

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Whether the eight bytes of `word` are all '0'..'9' (each high nibble 3, and adding 6 keeps it).
inline bool eight_digits(std::uint64_t word) {
  return (word & 0xF0F0F0F0F0F0F0F0u) == 0x3030303030303030u &&
         ((word + 0x0606060606060606u) & 0xF0F0F0F0F0F0F0F0u) == 0x3030303030303030u;
}

#if defined(__SSE2__)
// Number of leading ASCII digits among the 16 bytes at p (16 when all are digits): one
// vector compare instead of a loop over the bytes.
inline unsigned leading_digits16(const char* p) {
  const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  const __m128i offset = _mm_sub_epi8(bytes, _mm_set1_epi8('0'));
  const __m128i digit = _mm_cmpeq_epi8(_mm_min_epu8(offset, _mm_set1_epi8(9)), offset);
  return static_cast<unsigned>(std::countr_zero(~static_cast<unsigned>(_mm_movemask_epi8(digit))));
}
#endif

// Skips a run of digits: 16 bytes per step while 16 more bytes are in [p, end) (SSE2),
// otherwise byte by byte (the buffer ends in '\n', which stops the loop).
inline const char* skip_digits(const char* p, const char* end) {
#if defined(__SSE2__)
  while (end - p >= 16) {
    const unsigned n = leading_digits16(p);
    p += n;
    if (n < 16) return p;
  }
#else
  (void)end;
#endif
  while (is_digit(*p)) ++p;
  return p;
}

// End of a number of the form [+-] digits [. digits] [(e|E) [+-] digits] (a digit in the
// mantissa required) starting at p, or nullptr. Every text of this form is a number for
// parse_number (fast_float), so a cell that passes here is one the line parser accepts.
inline const char* skip_number(const char* p, const char* end) {
  // The sign of a measured value is random: stepping over a '-' without a branch saves a
  // mispredicted jump on half the cells.
  const bool minus = *p == '-';
  p += minus;
  if (*p == '+' && !minus && (is_digit(p[1]) || p[1] == '.')) ++p;
  const char* mantissa = p;
  p = skip_digits(p, end);
  std::size_t digits = static_cast<std::size_t>(p - mantissa);
  if (*p == '.') {
    const char* fraction = ++p;
    p = skip_digits(p, end);
    digits += static_cast<std::size_t>(p - fraction);
  }
  if (digits == 0) return nullptr;
  if (*p == 'e' || *p == 'E') {
    const char* q = p + 1;
    if (*q == '+' || *q == '-') ++q;
    if (!is_digit(*q)) return nullptr;
    while (is_digit(*q)) ++q;
    p = q;
  }
  return p;
}

// A decimal number of the skip_number form, scanned once: its end, and when it is simple
// enough its exact value by Clinger's fast path (at most 19 digits whose value is below 2^53,
// |power of ten| <= 22: the integer and the power are exact doubles, so one multiplication or
// division rounds once, correctly, to the same bits as strtod and fast_float). `exact` is false
// when the caller must convert the text with fast_float instead.
struct Scanned {
  const char* end = nullptr;  // nullptr: not a number of that form
  double value = 0.0;
  bool exact = false;
};

inline std::uint64_t eight_digit_value(std::uint64_t word) {
  word = ((word & 0x0F0F0F0F0F0F0F0Fu) * 2561) >> 8;
  word = ((word & 0x00FF00FF00FF00FFu) * 6553601) >> 16;
  return ((word & 0x0000FFFF0000FFFFu) * 42949672960001u) >> 32;
}

// Appends the digits at p to mantissa (wrapping past 19 digits: the caller then does not use
// it), eight at a time while eight bytes remain before end; returns the end of the digits.
inline const char* read_digits(const char* p, const char* end, std::uint64_t& mantissa) {
  while (end - p >= 8) {
    std::uint64_t word;
    std::memcpy(&word, p, 8);
    if (!eight_digits(word)) break;
    mantissa = mantissa * 100000000u + eight_digit_value(word);
    p += 8;
  }
  while (is_digit(*p)) {
    mantissa = mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
    ++p;
  }
  return p;
}

inline Scanned scan_decimal(const char* p, const char* end) {
  static constexpr double kPowers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  Scanned out;
  const bool negative = *p == '-';  // without a branch, as in skip_number
  p += negative;
  if (*p == '+' && !negative && (is_digit(p[1]) || p[1] == '.')) ++p;
  std::uint64_t mantissa = 0;
  const char* integer = p;
  p = read_digits(p, end, mantissa);
  long long exponent = 0;
  std::size_t total = static_cast<std::size_t>(p - integer);
  if (*p == '.') {
    ++p;
    const char* fraction = p;
    p = read_digits(p, end, mantissa);
    const auto fraction_digits = static_cast<std::size_t>(p - fraction);
    total += fraction_digits;
    exponent = -static_cast<long long>(fraction_digits);
  }
  if (total == 0) return out;
  if (*p == 'e' || *p == 'E') {
    const char* q = p + 1;
    bool negative_exponent = false;
    if (*q == '+' || *q == '-') negative_exponent = *q++ == '-';
    if (!is_digit(*q)) return out;
    long long written = 0;
    const char* first = q;
    while (is_digit(*q)) {
      if (q - first < 6) written = written * 10 + (*q - '0');
      ++q;
    }
    if (q - first >= 6) written = 1'000'000;  // far outside the fast path either way
    exponent += negative_exponent ? -written : written;
    p = q;
  }
  out.end = p;
  if (total <= 19 && mantissa <= (std::uint64_t{1} << 53) && exponent >= -22 && exponent <= 22) {
    const auto m = static_cast<double>(mantissa);
    const double magnitude = exponent >= 0 ? m * kPowers[exponent] : m / kPowers[-exponent];
    out.value = std::bit_cast<double>(std::bit_cast<std::uint64_t>(magnitude) |
                                      (std::uint64_t{negative} << 63));
    out.exact = true;
  }
  return out;
}

// Parses the plain rows of [begin, end) (complete lines, the last ending in '\n') into `out` and
// returns where the first other line starts (end when all were plain). A line that is not plain
// stores nothing.
std::size_t parse_plain_rows(const char* begin, const char* end, const RowLayout& layout,
                             PlainRows& out) {
  const bool words = layout.separator == Separator::whitespace;
  const char sep = separator_char(layout.separator);
  // Blanks the line parser trims around a cell; a tab is the separator in tab-separated files.
  // (One comparison for the usual byte, a digit or sign above ' '.)
  const auto blank = [sep](char c) {
    return static_cast<unsigned char>(c) <= ' ' && (c == ' ' || (c == '\t' && sep != '\t'));
  };
  const std::size_t last_column = layout.columns - 1;
  const std::size_t time_column = layout.time_column ? *layout.time_column : layout.columns;
  const char* p = begin;
  while (p < end) {
    const char* q = p;
    while (blank(*q)) ++q;
    double value = 0.0;
    SplitTime time;
    const char* time_begin = nullptr;
    const char* time_end = nullptr;
    bool plain = true;
    for (std::size_t column = 0; plain; ++column) {
      if (column == layout.value_column) {
        const Scanned number = scan_decimal(q, end);
        if (number.end == nullptr) {
          plain = false;
        } else if (number.exact) {
          value = number.value;
          q = number.end;
        } else {  // the same text, converted as parse_number does
          const char* first = q;
          if (*first == '+') ++first;
          const auto result = fast_float::from_chars(first, number.end, value);
          plain = result.ec == std::errc() && result.ptr == number.end && std::isfinite(value);
          q = number.end;
        }
      } else if (column == time_column) {
        const char* stop = q;
        while (!blank(*stop) && *stop != sep && *stop != '\r' && *stop != '\n') ++stop;
        const auto parsed = parse_split_time(std::string_view(q, static_cast<std::size_t>(stop - q)));
        plain = parsed && is_finite(*parsed);
        if (plain) time = *parsed;
        time_begin = q;
        time_end = stop;
        q = stop;
      } else {
        q = skip_number(q, end);
        plain = q != nullptr;
      }
      if (!plain) break;
      const char* after = q;
      while (blank(*q)) ++q;
      if (column == last_column) break;
      if (words) {
        plain = q != after;  // cells are separated by at least one blank
      } else if (*q == sep) {  // never step past a '\n': it may end the buffer
        ++q;
        while (blank(*q)) ++q;
      } else {
        plain = false;
      }
    }
    if (!plain) break;
    if (*q == '\r') ++q;
    if (*q != '\n') break;
    out.values.push_back(value);
    if (time_begin != nullptr) {
      if (out.times.empty()) out.first_time.assign(time_begin, time_end);
      out.times.push_back(time);
    }
    ++out.rows;
    p = q + 1;
  }
  return static_cast<std::size_t>(p - begin);
}

// --- the row pool --------------------------------------------------------------------------------
// Parses a long run of complete lines in chunks of about `chunk_bytes` (cut just after a '\n',
// so every chunk is whole lines) on worker threads that live as long as the reader, while the
// calling thread takes the finished chunks in file order (and parses chunks itself whenever the
// next one in order is not ready). At most kWindow chunks are parsed ahead of the one being
// taken, so memory stays a few chunks' rows whatever the file size. A chunk's boundaries depend
// only on the bytes and the chunk size, never on which thread parses it, so results cannot
// depend on the thread count.
class RowPool {
 public:
  struct Chunk {
    PlainRows rows;
    std::size_t begin = 0;  // byte range of the chunk in the run
    std::size_t end = 0;
    std::size_t stop = 0;   // bytes from begin the row parser took (end - begin: all)
    bool done = false;
  };

  explicit RowPool(unsigned helpers) {
    workers_.reserve(helpers);
    for (unsigned i = 0; i < helpers; ++i) workers_.emplace_back([this] { work(); });
  }
  RowPool(const RowPool&) = delete;
  RowPool& operator=(const RowPool&) = delete;
  ~RowPool() {
    {
      std::lock_guard lock(mutex_);
      quit_ = true;
    }
    work_ready_.notify_all();
    for (auto& worker : workers_) worker.join();
  }

  /// Parses [data, data + size) (complete lines, the last ending in '\n') and calls take(chunk)
  /// for every chunk in order on the calling thread. If take throws, the workers finish the
  /// chunks they hold (they never touch the data after run returns) and the exception goes on.
  template <class Take>
  void run(const char* data, std::size_t size, std::size_t chunk_bytes, const RowLayout& layout,
           Take&& take) {
    const std::size_t count = (size + chunk_bytes - 1) / chunk_bytes;
    {
      std::lock_guard lock(mutex_);
      data_ = data;
      size_ = size;
      chunk_bytes_ = chunk_bytes;
      layout_ = layout;
      count_ = count;
      claimed_ = 0;
      taken_ = 0;
      for (auto& slot : slots_) slot.done = false;
    }
    work_ready_.notify_all();
    struct Close {  // stops the claiming and waits for chunks in flight, also when take throws
      RowPool& pool;
      ~Close() {
        std::unique_lock lock(pool.mutex_);
        pool.count_ = 0;
        pool.chunk_done_.wait(lock, [&] { return pool.in_flight_ == 0; });
      }
    } close{*this};
    for (std::size_t k = 0; k < count; ++k) {
      Chunk& slot = slots_[k % kWindow];
      {
        std::unique_lock lock(mutex_);
        while (!slot.done) {
          if (claimable()) {  // help rather than wait
            parse_claimed(lock);
          } else {
            chunk_done_.wait(lock);
          }
        }
      }
      take(slot);
      {
        std::lock_guard lock(mutex_);
        slot.done = false;
        ++taken_;
      }
      if (!workers_.empty()) work_ready_.notify_all();
    }
  }

 private:
  static constexpr std::size_t kWindow = 32;

  bool claimable() const { return claimed_ < count_ && claimed_ < taken_ + kWindow; }

  // Start of chunk k: just after the first '\n' at or after its nominal start.
  std::size_t chunk_start(std::size_t k) const {
    if (k == 0) return 0;
    const std::size_t nominal = k * chunk_bytes_;
    if (nominal >= size_) return size_;
    const void* newline = std::memchr(data_ + nominal - 1, '\n', size_ - nominal + 1);
    return static_cast<std::size_t>(static_cast<const char*>(newline) - data_) + 1;
  }

  // Claims the next chunk (lock held on entry and exit) and parses it without the lock.
  void parse_claimed(std::unique_lock<std::mutex>& lock) {
    const std::size_t k = claimed_++;
    ++in_flight_;
    Chunk& slot = slots_[k % kWindow];
    lock.unlock();
    slot.rows.clear();
    slot.begin = chunk_start(k);
    slot.end = std::max(slot.begin, chunk_start(k + 1));
    slot.stop = parse_plain_rows(data_ + slot.begin, data_ + slot.end, layout_, slot.rows);
    lock.lock();
    slot.done = true;
    --in_flight_;
    chunk_done_.notify_all();
  }

  void work() {
    std::unique_lock lock(mutex_);
    for (;;) {
      work_ready_.wait(lock, [&] { return quit_ || claimable(); });
      if (quit_) return;
      parse_claimed(lock);
    }
  }

  std::mutex mutex_;
  std::condition_variable work_ready_;  // a chunk can be claimed, or quit
  std::condition_variable chunk_done_;  // a chunk finished
  std::array<Chunk, kWindow> slots_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t chunk_bytes_ = 1;
  RowLayout layout_{};
  std::size_t count_ = 0;    // chunks in the current run (0: none to claim)
  std::size_t claimed_ = 0;  // chunks handed to a thread
  std::size_t taken_ = 0;    // chunks taken by run's caller
  std::size_t in_flight_ = 0;
  bool quit_ = false;
  std::vector<std::thread> workers_;
};

// The state machine over lines: first content line (header or data), then data rows.
class TextParser {
 public:
  TextParser(std::string_view source, const TextReadOptions& options) : options_(options) {
    out_.source = std::string(source);
  }

  void operator()(std::string_view line) {
    ++line_number_;
    if (line_number_ == 1) line = strip_byte_order_mark(line);
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view content = trim(line);
    if (content.empty()) return;
    if (out_.column_count == 0) {
      first_content_line(content);
    } else {
      data_row(content);
    }
  }

  /// Whether whole blocks may go to bulk(): the first row has fixed the layout.
  [[nodiscard]] bool bulk_ready() const { return options_.bulk_rows && out_.column_count != 0; }

  /// Complete LF-terminated lines (size > 0, data[size - 1] == '\n'): cut at line ends into
  /// chunks parsed by parse_plain_rows on the row pool, and taken in file order; a line the row
  /// parser leaves goes through operator() with its exact line number.
  void bulk(const char* data, std::size_t size) {
    const RowLayout layout{out_.separator, out_.column_count, out_.value_column, out_.time_column};
    const std::size_t chunk_bytes = std::clamp<std::size_t>(options_.block_bytes, 1, kChunkBytes);
    auto take_chunk = [&](RowPool::Chunk& chunk) {
      if (chunk.begin == 0 && chunk.rows.rows > 0) reserve_for(chunk, size);
      take(chunk.rows);
      const char* p = data + chunk.begin + chunk.stop;
      const char* const end = data + chunk.end;
      while (p < end) {
        const char* newline = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
        std::string_view line(p, static_cast<std::size_t>(newline - p));
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        (*this)(line);
        p = newline + 1;
        leftover_.clear();
        p += parse_plain_rows(p, end, layout, leftover_);
        take(leftover_);
      }
      if (consumed_) consumed_(end);
    };
    const unsigned threads = imunoise::detail::resolve_threads(options_.threads);
    if (threads > 1 && size > chunk_bytes) {
      // Threads start once per read, not per block, and wait between blocks.
      if (!pool_) pool_ = std::make_unique<RowPool>(threads - 1);
      pool_->run(data, size, chunk_bytes, layout, take_chunk);
    } else {
      RowPool alone(0);
      alone.run(data, size, chunk_bytes, layout, take_chunk);
    }
  }

  /// Reserves the output for the rows of `size` bytes, estimated from the first chunk's bytes
  /// per row (5 % more): growing by doubling copied the values and touched fresh pages each time
  /// (page faults in that copy were 7 % of a read's cycles). Capacity never written costs no
  /// memory, and a wrong estimate only means the vectors grow as before.
  void reserve_for(const RowPool::Chunk& first, std::size_t size) {
    const double rows_per_byte = static_cast<double>(first.rows.rows) / static_cast<double>(first.end);
    const auto expected = std::min(size / 2, static_cast<std::size_t>(rows_per_byte * static_cast<double>(size) * 1.05)) +
                          out_.values.size() + 16;
    if (expected <= out_.values.capacity()) return;
    // At least doubling: a stream's blocks each come here, and must not reallocate per block.
    const std::size_t target = std::max(expected, 2 * out_.values.capacity());
    out_.values.reserve(target);
    if (out_.time_column) times_.reserve(target);
  }

  /// Called with the end of every chunk taken by bulk(): the bytes before it are no longer
  /// needed (read_text_file drops them from its memory map).
  void on_consumed(std::function<void(const char*)> consumed) { consumed_ = std::move(consumed); }

  TextColumns finish() {
    if (out_.column_count == 0) {
      if (line_number_ == 0) fail(0, "empty file (no bytes)", "check that the right file was given");
      fail(0, "no data lines (only comments and blank lines)",
           "give a file with one sample per line; '#' starts a comment");
    }
    if (out_.values.empty()) {
      fail(out_.header_line, "header line but no data rows after it",
           "add the data rows below the header");
    }
    if (out_.time_column) finish_time();
    return std::move(out_);
  }

 private:
  std::string_view strip_byte_order_mark(std::string_view line) const {
    if (line.substr(0, 3) == "\xEF\xBB\xBF") return line.substr(3);
    if (line.substr(0, 2) == "\xFF\xFE" || line.substr(0, 2) == "\xFE\xFF") {
      fail(1, "the file is UTF-16 encoded", "save it as UTF-8 or ASCII text");
    }
    return line;
  }

  // A line is a header when none of its fields is a number; otherwise it is the first data row.
  void first_content_line(std::string_view content) {
    out_.separator = detect_separator(content);
    std::vector<std::string> fields;
    bool any_number = false;
    FieldCursor cursor(content, out_.separator);
    std::string_view field;
    while (cursor.next(field)) {
      any_number = any_number || parse_number(field).has_value();
      fields.emplace_back(field);
    }
    out_.column_count = fields.size();
    if (!any_number) {
      out_.header = std::move(fields);
      out_.header_line = line_number_;
      resolve_columns();
      return;
    }
    resolve_columns();
    data_row(content);
  }

  void data_row(std::string_view content) {
    if (out_.first_data_line == 0) out_.first_data_line = line_number_;
    FieldCursor cursor(content, out_.separator);
    std::string_view field;
    std::size_t column = 0;
    while (cursor.next(field)) {
      if (column == out_.column_count) ragged(column + 1 + cursor.count_rest());
      if (column == out_.value_column) {
        out_.values.push_back(value_cell(field, column));
      } else if (out_.time_column && column == *out_.time_column) {
        time_cell(field, column);
      } else if (!parse_number(field)) {
        not_a_number(field, column);
      }
      ++column;
    }
    if (column != out_.column_count) ragged(column);
    out_.lines.add(rows_, line_number_);
    ++rows_;
  }

  double value_cell(std::string_view field, std::size_t column) const {
    const std::optional<double> value = parse_number(field);
    if (!value) not_a_number(field, column);
    if (!std::isfinite(*value)) not_finite(field, column, non_finite_reason(field));
    return *value;
  }

  void time_cell(std::string_view field, std::size_t column) {
    const std::optional<SplitTime> time = parse_split_time(field);
    if (!time) not_a_number(field, column);
    if (!is_finite(*time)) not_finite(field, column, non_finite_reason(field));
    if (times_.empty()) out_.time_origin = std::string(field);
    times_.push_back(*time);
  }

  void finish_time() {
    if (options_.time_unit) {
      if (options_.time_unit->quantity != Quantity::time) {
        fail(0, "time unit '" + options_.time_unit->name + "' is not a unit of time",
             "give the time column's unit as s, ms, us or ns");
      }
      out_.time_unit = *options_.time_unit;
    } else {
      out_.time_unit = parse_unit(looks_like_nanoseconds(times_) ? "ns" : "s");
    }
    out_.time_s = relative_seconds(times_, out_.time_unit.to_si);
    // Each time is finite, but two near the ends of the double range differ by infinity.
    for (std::size_t i = 0; i < out_.time_s.size(); ++i) {
      if (!std::isfinite(out_.time_s[i])) {
        fail(out_.line_of(i),
             "sample " + std::to_string(i) + ", " + column_label(*out_.time_column) +
                 ": the time since the first sample overflows a double",
             "check the time column (--time-column) and its unit");
      }
    }
  }

  // --- column selection ----------------------------------------------------------------------

  void resolve_columns() {
    const std::size_t line = line_number_;
    std::optional<std::size_t> time;
    if (options_.time_column) time = resolve(*options_.time_column, "--time-column", line);
    std::size_t value = 0;
    if (options_.column) {
      value = resolve(*options_.column, "--column", line);
    } else if (out_.column_count == 1 && !time) {
      value = 0;
    } else if (out_.column_count == 2 && time) {
      value = 1 - *time;
    } else if (out_.column_count == 1) {
      fail(line, "the only column is the time column, so no column is left for the values",
           "give a file with a value column, or drop --time-column");
    } else {
      fail(line, "the rows have " + column_list() + ", and no value column was chosen",
           "pass --column with a 0-based index or a header name");
    }
    if (time && *time == value) {
      fail(line, "the time column and the value column are both column " + std::to_string(value),
           "choose different columns with --column and --time-column");
    }
    out_.value_column = value;
    out_.time_column = time;
  }

  std::size_t resolve(const ColumnSelector& selector, std::string_view option,
                      std::size_t line) const {
    if (const auto* index = std::get_if<std::size_t>(&selector)) {
      if (*index < out_.column_count) return *index;
      fail(line,
           "column " + std::to_string(*index) + " (" + std::string(option) +
               ") does not exist: the rows have " + column_list(),
           "pass " + std::string(option) + " with a 0-based index below " +
               std::to_string(out_.column_count) + " or a header name");
    }
    const std::string& name = std::get<std::string>(selector);
    if (out_.header.empty()) {
      fail(line,
           "column " + quoted_name(name) + " (" + std::string(option) +
               ") cannot be found: the file has no header line; the rows have " + column_list(),
           "pass " + std::string(option) + " with a 0-based index, or add a header line");
    }
    std::vector<std::size_t> matches;
    for (std::size_t i = 0; i < out_.header.size(); ++i) {
      if (out_.header[i] == name) matches.push_back(i);
    }
    if (matches.size() == 1) return matches.front();
    const std::string problem = matches.empty() ? " does not exist" : " names more than one column";
    fail(line,
         "column " + quoted_name(name) + " (" + std::string(option) + ")" + problem +
             "; the header has " + column_list(),
         "pass " + std::string(option) + " with a 0-based index or a unique header name");
  }

  // "3 columns: 0 "t", 1 "gx", 2 "gy"" or "0..2 (no header line)".
  std::string column_list() const {
    const std::size_t n = out_.column_count;
    if (out_.header.empty()) {
      return std::to_string(n) + (n == 1 ? " column" : " columns") + ", 0.." +
             std::to_string(n - 1) + " (no header line)";
    }
    std::string text = std::to_string(n) + (n == 1 ? " column:" : " columns:");
    for (std::size_t i = 0; i < n && i < listed_columns_max; ++i) {
      text += (i == 0 ? " " : ", ") + std::to_string(i) + " " + quoted_name(out_.header[i]);
    }
    if (n > listed_columns_max) text += ", ...";
    return text;
  }

  std::string column_label(std::size_t column) const {
    std::string label = "column " + std::to_string(column);
    if (column < out_.header.size()) label += " " + quoted_name(out_.header[column]);
    return label;
  }

  // --- errors --------------------------------------------------------------------------------

  [[noreturn]] void fail(std::size_t line, const std::string& what, const std::string& fix) const {
    std::string where = out_.source + ":";
    if (line != 0) where += std::to_string(line) + ":";
    throw InputError(where + " " + what + "; fix: " + fix);
  }

  [[noreturn]] void not_a_number(std::string_view field, std::size_t column) const {
    if (field.empty()) {
      fail(line_number_, column_label(column) + ": empty cell",
           "fill in the cell or comment the row out with '#'");
    }
    std::string fix = "correct the cell or comment the row out with '#'; cells must be numbers "
                      "written with '.' as the decimal point";
    if (field.find(',') != std::string_view::npos) fix += " (not ',')";
    if (line_number_ == out_.first_data_line) {
      fix += out_.header.empty()
                 ? "; the first line is a header only when none of its fields is a number"
                 : "; only one header line is allowed";
    }
    fail(line_number_, column_label(column) + ": " + excerpt(field) + " is not a number", fix);
  }

  [[noreturn]] void not_finite(std::string_view field, std::size_t column,
                               const std::string& reason) const {
    fail(line_number_,
         "sample " + std::to_string(rows_) + ", " + column_label(column) + ": " + excerpt(field) + " " + reason,
         "repair or remove the row; imunoise never skips or fills in samples");
  }

  [[noreturn]] void ragged(std::size_t fields) const {
    const std::string reference = out_.header_line != 0
                                      ? "the header (line " + std::to_string(out_.header_line) + ")"
                                      : "the first data row (line " +
                                            std::to_string(out_.first_data_line) + ")";
    fail(line_number_,
         std::to_string(fields) + (fields == 1 ? " field" : " fields") + ", but " + reference +
             " has " + std::to_string(out_.column_count) + " (fields separated by " +
             std::string(separator_name(out_.separator)) + ", detected on line " +
             std::to_string(out_.header_line != 0 ? out_.header_line : out_.first_data_line) + ")",
         "give every row the same number of fields, or comment the row out with '#'");
  }

  // Rows from parse_plain_rows that follow the lines read so far.
  void take(PlainRows& rows) {
    if (rows.rows == 0) return;
    if (out_.first_data_line == 0) out_.first_data_line = line_number_ + 1;
    out_.lines.add(rows_, line_number_ + 1);
    out_.values.insert(out_.values.end(), rows.values.begin(), rows.values.end());
    if (out_.time_column) {
      if (times_.empty()) out_.time_origin = rows.first_time;
      times_.insert(times_.end(), rows.times.begin(), rows.times.end());
    }
    line_number_ += rows.rows;
    rows_ += rows.rows;
  }

  // Bytes per chunk of bulk(): a few milliseconds of parsing, so that two threads share the
  // work evenly and the rows parsed ahead of the one being taken stay small.
  static constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

  // Declared before the pool: its threads are joined first, and never outlive the parser.
  PlainRows leftover_;  // bulk(): rows after a line the row parser left
  std::function<void(const char*)> consumed_;
  std::unique_ptr<RowPool> pool_;
  TextReadOptions options_;
  TextColumns out_;
  std::size_t line_number_ = 0;
  std::size_t rows_ = 0;  // data rows completed so far = index of the row being read
  std::vector<SplitTime> times_;
};

struct FileCloser {
  void operator()(std::FILE* file) const noexcept { std::fclose(file); }
};

// A regular, non-empty file mapped read-only; data() is nullptr when the file is anything else
// or cannot be mapped (the caller then reads it in blocks).
class MappedText {
 public:
  explicit MappedText(int fd) {
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) return;
    const auto size = static_cast<std::size_t>(st.st_size);
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (map == MAP_FAILED) return;
    ::madvise(map, size, MADV_SEQUENTIAL);
    data_ = static_cast<const char*>(map);
    size_ = size;
  }
  MappedText(const MappedText&) = delete;
  MappedText& operator=(const MappedText&) = delete;
  ~MappedText() {
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  [[nodiscard]] const char* data() const { return data_; }
  [[nodiscard]] std::size_t size() const { return size_; }

  /// Drops the pages wholly before `end` from this process (they stay in the page cache), so
  /// that resident memory does not grow with the file.
  void release_before(const char* end) const {
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const std::size_t upto = static_cast<std::size_t>(end - data_) / page * page;
    if (upto > released_) {
      ::madvise(const_cast<char*>(data_) + released_, upto - released_, MADV_DONTNEED);
      released_ = upto;
    }
  }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  mutable std::size_t released_ = 0;
};

}  // namespace

// --- public helpers ------------------------------------------------------------------------------

std::optional<double> parse_number(std::string_view text) {
  const char* first = text.data();
  const char* last = first + text.size();
  // fast_float follows std::from_chars, which rejects a leading '+'; files often have one.
  if (last - first >= 2 && *first == '+' &&
      ((first[1] >= '0' && first[1] <= '9') || first[1] == '.')) {
    ++first;
  }
  double value = 0.0;
  const auto result = fast_float::from_chars(first, last, value);
  if (result.ec != std::errc() || result.ptr != last || first == last) return std::nullopt;
  return value;
}

ColumnSelector parse_column_selector(std::string_view text) {
  const std::string_view name = trim(text);
  if (name.empty()) {
    throw InputError("empty column selector; fix: pass --column with a 0-based index or a "
                     "header name");
  }
  if (name.find_first_not_of("0123456789") != std::string_view::npos) return std::string(name);
  std::size_t index = 0;
  const auto result = std::from_chars(name.data(), name.data() + name.size(), index);
  if (result.ec != std::errc()) {
    throw InputError("column index " + excerpt(name) + " is too large; fix: pass a 0-based "
                     "column index or a header name");
  }
  return index;
}

std::string describe_column_selector(const ColumnSelector& selector) {
  if (const auto* index = std::get_if<std::size_t>(&selector)) {
    return "column " + std::to_string(*index);
  }
  return "column " + quoted_name(std::get<std::string>(selector));
}

std::string_view separator_name(Separator separator) {
  switch (separator) {
    case Separator::comma: return "comma";
    case Separator::tab: return "tab";
    case Separator::semicolon: return "semicolon";
    case Separator::whitespace: return "whitespace";
  }
  return "unknown";
}

void LineMap::add(std::size_t sample, std::size_t line) {
  if (!runs_.empty()) {
    const Run& last = runs_.back();
    if (sample >= last.first_sample && line - last.first_line == sample - last.first_sample) return;
  }
  runs_.push_back({sample, line});
}

std::vector<std::string> split_fields(std::string_view line) {
  line = trim(line);
  std::vector<std::string> fields;
  if (line.empty()) return fields;
  FieldCursor cursor(line, detect_separator(line));
  std::string_view field;
  while (cursor.next(field)) fields.emplace_back(field);
  return fields;
}

std::size_t LineMap::line_of(std::size_t sample) const {
  if (runs_.empty()) return 0;
  auto it = std::upper_bound(runs_.begin(), runs_.end(), sample,
                             [](std::size_t s, const Run& run) { return s < run.first_sample; });
  if (it == runs_.begin()) return 0;
  --it;
  return it->first_line + (sample - it->first_sample);
}

// --- readers -------------------------------------------------------------------------------------

TextColumns read_text_buffer(std::string_view text, std::string_view source,
                             const TextReadOptions& options) {
  TextParser parser(source, options);
  LineSplitter<TextParser> splitter(parser);
  splitter.process(text.data(), text.size(), true);
  return parser.finish();
}

TextColumns read_text_stream(std::istream& in, std::string_view source,
                             const TextReadOptions& options) {
  TextParser parser(source, options);
  auto read = [&](char* destination, std::size_t capacity) -> std::size_t {
    in.read(destination, static_cast<std::streamsize>(capacity));
    if (in.bad()) {
      throw InputError(std::string(source) + ": read error; fix: check the input stream");
    }
    return static_cast<std::size_t>(in.gcount());
  };
  split_blocks(read, options.block_bytes, parser);
  return parser.finish();
}

TextColumns read_text_file(const std::filesystem::path& path, const TextReadOptions& options) {
  const std::string source = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(source + ": is a directory; fix: give the path of a text file");
  }
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(source.c_str(), "rb"));
  if (!file) {
    throw InputError(source + ": cannot open (" + std::strerror(errno) +
                     "); fix: check the path and the permissions");
  }
  // A regular file is mapped and parsed in place: no copy, and the reading (page faults on the
  // mapping) happens in the parsing threads, overlapped, instead of between blocks. Pipes and
  // anything that cannot be mapped are read in blocks.
  if (const MappedText mapped(fileno(file.get())); mapped.data() != nullptr) {
    TextParser parser(source, options);
    parser.on_consumed([&mapped](const char* end) { mapped.release_before(end); });
    LineSplitter<TextParser> splitter(parser);
    splitter.process(mapped.data(), mapped.size(), true);
    return parser.finish();
  }
  // Blocks go straight into our buffer; stdio's own buffer would only add a copy.
  std::setvbuf(file.get(), nullptr, _IONBF, 0);
  TextParser parser(source, options);
  auto read = [&](char* destination, std::size_t capacity) -> std::size_t {
    const std::size_t got = std::fread(destination, 1, capacity, file.get());
    if (got == 0 && std::ferror(file.get())) {
      throw InputError(source + ": read error (" + std::strerror(errno) +
                       "); fix: check the file and the disk");
    }
    return got;
  };
  split_blocks(read, options.block_bytes, parser);
  return parser.finish();
}

}  // namespace imunoise::io
