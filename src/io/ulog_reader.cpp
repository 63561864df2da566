// PX4 ULog (https://docs.px4.io/main/en/dev_log/ulog_file_format.html), read without a ULog
// library (none is packaged in Debian).
//
// A file is a 16-byte header ("ULog\x01\x12\x35", version, start time in µs), then messages
// (uint16 size, uint8 type, `size` bytes). The definitions section holds the flag bits ('B',
// first), message formats ('F': "name:type field;type[N] field;..."), information ('I', 'M')
// and parameters ('P', 'Q'); the data section, from the first subscription on, holds
// subscriptions ('A': multi_id, msg_id, format name), their data ('D': msg_id, then the fields
// of the format, packed little-endian, the first the uint64 timestamp in µs), log text ('L',
// 'C'), sync markers ('S') and dropouts ('O': uint16 ms the logger lost). A trailing padding
// field of a format is not written, so a 'D' message may be shorter than its format.
//
// IMU topics read: sensor_combined, vehicle_imu (delta angle and velocity over their dt,
// converted to rates), vehicle_angular_velocity, vehicle_acceleration, sensor_gyro and
// sensor_accel; one instance (multi_id) gives gyro_x..accel_z, several give gyro0_x ...
#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <fmt/core.h>

#include "byte_cursor.hpp"
#include "imunoise/io/imu_containers.hpp"
#include "imunoise/io/timestamps.hpp"

namespace imunoise::io {
namespace {

using detail::ByteCursor;

constexpr std::string_view kMagic{"ULog\x01\x12\x35", 7};
constexpr std::size_t kHeaderBytes = 16;
constexpr int kMaxNesting = 16;  // formats nest (a field of another format's type); cycles are corrupt

enum class Base { i8, u8, i16, u16, i32, u32, i64, u64, f32, f64, boolean, character, nested };

struct Field {
  Base base = Base::u8;
  std::string type;  // the nested format's name, or the base type's
  std::size_t count = 1;
  std::string name;
};

std::optional<Base> base_of(std::string_view t) {
  static const std::pair<std::string_view, Base> names[] = {
      {"int8_t", Base::i8},   {"uint8_t", Base::u8},   {"int16_t", Base::i16}, {"uint16_t", Base::u16},
      {"int32_t", Base::i32}, {"uint32_t", Base::u32}, {"int64_t", Base::i64}, {"uint64_t", Base::u64},
      {"float", Base::f32},   {"double", Base::f64},   {"bool", Base::boolean}, {"char", Base::character}};
  for (const auto& [n, b] : names) {
    if (t == n) return b;
  }
  return std::nullopt;
}

std::size_t size_of(Base b) {
  switch (b) {
    case Base::i8: case Base::u8: case Base::boolean: case Base::character: return 1;
    case Base::i16: case Base::u16: return 2;
    case Base::i32: case Base::u32: case Base::f32: return 4;
    case Base::i64: case Base::u64: case Base::f64: return 8;
    case Base::nested: return 0;
  }
  return 0;
}

// A numeric field read from a data message (little-endian, any alignment).
double value_at(const unsigned char* p, Base b) {
  auto le = [p](auto zero) {  // assembled byte by byte: compilers make it one load
    using T = decltype(zero);
    T v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) v = static_cast<T>(v | static_cast<T>(T{p[i]} << (8 * i)));
    return v;
  };
  switch (b) {
    case Base::i8: return static_cast<double>(static_cast<std::int8_t>(p[0]));
    case Base::u8: case Base::boolean: case Base::character: return p[0];
    case Base::i16: return static_cast<std::int16_t>(le(std::uint16_t{}));
    case Base::u16: return le(std::uint16_t{});
    case Base::i32: return static_cast<std::int32_t>(le(std::uint32_t{}));
    case Base::u32: return le(std::uint32_t{});
    case Base::i64: return static_cast<double>(static_cast<std::int64_t>(le(std::uint64_t{})));
    case Base::u64: return static_cast<double>(le(std::uint64_t{}));
    case Base::f32: return std::bit_cast<float>(le(std::uint32_t{}));
    case Base::f64: return std::bit_cast<double>(le(std::uint64_t{}));
    case Base::nested: return 0.0;
  }
  return 0.0;
}

std::uint64_t u64_at(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= std::uint64_t{p[i]} << (8 * i);
  return v;
}

// Text from the file as it may be quoted in a message: bytes outside printable ASCII as \xNN
// (a NUL would end the message early).
std::string shown(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    const auto b = static_cast<unsigned char>(ch);
    if (b >= 0x20 && b < 0x7f) out += ch;
    else out += fmt::format("\\x{:02x}", b);
  }
  return out;
}

// Where a field the reader needs sits in a data message (after the msg_id).
struct Slot {
  std::size_t offset = 0;
  Base base = Base::f32;
  std::size_t count = 1;
  [[nodiscard]] std::size_t end() const { return offset + size_of(base) * count; }
};

// What a topic's data message gives: up to six values (gyro x y z, accel x y z), each either a
// field or a delta over a dt field; the sample time; accel's own time offset (sensor_combined).
enum class Quantity { gyro, accel };
struct Vector3 {
  Quantity quantity;
  Slot value;                   // [3]-array or the first of three consecutive scalars x y z
  std::optional<Slot> dt_us;    // vehicle_imu: the value is a delta over dt (µs)
  std::optional<Slot> relative; // sensor_combined accel: its time relative to the timestamp (µs)
};
struct Layout {
  Slot time;  // uint64 µs
  std::vector<Vector3> vectors;
  std::size_t needed = 0;  // bytes of data a message must have
};

// The IMU topics read (layout() maps their fields to vectors).
constexpr std::string_view kImuTopics[] = {"sensor_combined", "vehicle_imu", "vehicle_angular_velocity",
                                           "vehicle_acceleration", "sensor_gyro", "sensor_accel"};

// One time series of three values for one instance (an instance of sensor_combined or
// vehicle_imu has two: gyro and accel, each with its own time).
struct Series {
  std::vector<std::int64_t> stamp_ns;
  std::vector<double> v[3];
};

class UlogReader {
 public:
  UlogReader(std::span<const unsigned char> bytes, std::string source, std::string topic)
      : bytes_(bytes), source_(std::move(source)), topic_(std::move(topic)) {}

  Recording read() {
    ByteCursor c(bytes_, source_);
    if (bytes_.size() < kMagic.size() || c.text(kMagic.size(), "magic") != kMagic) {
      throw InputError(source_ + ": not a PX4 ULog file (no ULog magic \"ULog\\x01\\x12\\x35\" at the start); "
                       "fix: give a .ulg log written by the PX4 logger");
    }
    c.u8("version");
    c.u64("start timestamp");
    bool first = true;
    while (!c.at_end()) {
      // The message header by hand: a cursor per message (it copies the file name) would
      // cost an allocation for each of millions of data messages.
      const std::size_t at = c.pos();
      // Data appended after a logger stop ('B' appended_offsets) may follow a message cut in
      // the middle, as the specification allows: a message crossing the offset is skipped.
      const auto next = std::upper_bound(appended_.begin(), appended_.end(), at);
      if (next != appended_.end() && (*next - at < 3 || (bytes_[at] | (std::size_t{bytes_[at + 1]} << 8)) > *next - at - 3)) {
        c.seek(*next, "appended data");
        continue;
      }
      if (c.remaining() < 3) c.fail("a message header needs 3 bytes (the log was cut short)");
      const unsigned char* h = bytes_.data() + at;
      const std::size_t size = h[0] | (std::size_t{h[1]} << 8);
      const std::uint8_t type = h[2];
      if (size > c.remaining() - 3) {
        c.fail(fmt::format("'{}' message of {} bytes, but only {} remain (the log was cut short)", printable(type), size,
                           c.remaining() - 3));
      }
      const std::span<const unsigned char> body(h + 3, size);
      c.seek(at + 3 + size, "next message");
      if (type == 'D') {
        data(body, at);
      } else if (type == 'O' || type == 'B' || type == 'F' || type == 'A' || type == 'R') {
        ByteCursor m(body, source_, at + 3);
        switch (type) {
          case 'B':
            if (!first) m.fail("flag bits ('B') message after the first message (corrupt)");
            flag_bits(m);
            break;
          case 'F': format(m, at); break;
          case 'A': subscribe(m); break;
          case 'R': decoder_[m.u16("msg_id")] = nullptr; break;
          default:
            ++dropouts_;
            dropout_ms_ += m.u16("dropout duration");
            break;
        }
      }
      // 'I', 'M', 'P', 'Q' (information, parameters), 'L', 'C' (log text), 'S' (sync) and
      // types a newer logger may add are skipped by their size, as the specification asks.
      first = false;
    }
    return recording();
  }

 private:
  // A refusal that is not corruption: the message says its own fix (ByteCursor::fail's is for
  // a damaged file).
  [[noreturn]] void refuse(const ByteCursor& m, const std::string& what_and_fix) const {
    throw InputError(fmt::format("{}: byte {}: {}", source_, m.base() + m.pos(), what_and_fix));
  }

  static std::string printable(std::uint8_t type) {
    return type >= 0x20 && type < 0x7f ? std::string(1, static_cast<char>(type)) : fmt::format("\\x{:02x}", type);
  }

  void flag_bits(ByteCursor& m) {
    m.take(8, "compat flags");
    const auto incompat = m.take(8, "incompat flags");
    if ((incompat[0] & 1u) != 0) {
      for (int i = 0; i < 3; ++i) {
        const std::uint64_t offset = m.u64("appended offset");
        if (offset > kHeaderBytes && offset < bytes_.size()) appended_.push_back(static_cast<std::size_t>(offset));
      }
      std::sort(appended_.begin(), appended_.end());
    }
    // Bit 0 of the first byte: data appended at the end (read sequentially like the rest).
    // Any other bit is a change of format this reader does not know: refuse, as the spec asks.
    if ((incompat[0] & ~1u) != 0 || std::any_of(incompat.begin() + 1, incompat.end(), [](auto b) { return b != 0; })) {
      refuse(m, "unknown incompatible flag bits are set (a newer ULog format than this reader knows); fix: export "
                "the IMU topic with a current pyulog (ulog2csv) and read the CSV file");
    }
  }

  void format(ByteCursor& m, std::size_t at) {
    const std::string_view text = m.text(m.remaining(), "format");
    const auto colon = text.find(':');
    if (colon == std::string_view::npos || colon == 0) m.fail("format message without 'name:' (corrupt)");
    std::vector<Field> fields;
    std::string_view rest = text.substr(colon + 1);
    while (!rest.empty()) {
      const auto semi = rest.find(';');
      const std::string_view item = rest.substr(0, semi);
      rest = semi == std::string_view::npos ? std::string_view{} : rest.substr(semi + 1);
      if (item.empty()) continue;
      const auto space = item.find(' ');
      if (space == std::string_view::npos) {
        throw InputError(fmt::format("{}: byte {}: format field '{}' is not 'type name'; fix: the log is corrupt, "
                                     "copy it again", source_, at, shown(item)));
      }
      Field f;
      std::string_view type = item.substr(0, space);
      f.name = std::string(item.substr(space + 1));
      if (const auto bracket = type.find('['); bracket != std::string_view::npos) {
        const auto close = type.find(']', bracket);
        std::size_t n = 0;
        bool ok = close != std::string_view::npos && close > bracket + 1;
        for (std::size_t i = bracket + 1; ok && i < close; ++i) {
          ok = type[i] >= '0' && type[i] <= '9' && n < 1'000'000;
          n = n * 10 + static_cast<std::size_t>(type[i] - '0');
        }
        if (!ok) {
          throw InputError(fmt::format("{}: byte {}: array size in '{}' is not a number; fix: the log is corrupt, "
                                       "copy it again", source_, at, shown(item)));
        }
        f.count = n;
        type = type.substr(0, bracket);
      }
      f.type = std::string(type);
      f.base = base_of(type).value_or(Base::nested);
      fields.push_back(std::move(f));
    }
    formats_[std::string(text.substr(0, colon))] = std::move(fields);
    sizes_.clear();
  }

  // Size of a format in bytes (nested formats included); nullopt when it names an unknown one,
  // nests in a cycle or too deep. Memoized: a hostile log could nest wide formats many levels
  // deep, which a plain recursion would expand exponentially.
  std::optional<std::size_t> format_size(const std::string& name, int depth) const {
    if (depth > kMaxNesting) return std::nullopt;
    if (const auto known = sizes_.find(name); known != sizes_.end()) return known->second;
    sizes_[name] = std::nullopt;  // while computing: a cycle back to it is unknown
    const auto it = formats_.find(name);
    if (it == formats_.end()) return std::nullopt;
    std::size_t total = 0;
    for (const auto& f : it->second) {
      std::size_t one = size_of(f.base);
      if (f.base == Base::nested) {
        const auto inner = format_size(f.type, depth + 1);
        if (!inner) return std::nullopt;
        one = *inner;
      }
      if (one != 0 && f.count > (std::size_t{1} << 32) / one) return std::nullopt;
      total += one * f.count;
      if (total > (std::size_t{1} << 32)) return std::nullopt;
    }
    sizes_[name] = total;
    return total;
  }

  // The slot of top-level field `name` in format `format` (nullopt when absent).
  std::optional<Slot> slot(const std::vector<Field>& fields, std::string_view name, ByteCursor& m) const {
    std::size_t offset = 0;
    for (const auto& f : fields) {
      if (f.name == name) return f.base == Base::nested ? std::nullopt : std::optional<Slot>(Slot{offset, f.base, f.count});
      std::size_t one = size_of(f.base);
      if (f.base == Base::nested) {
        const auto inner = format_size(f.type, 1);
        if (!inner) {
          m.fail("format of field '" + shown(f.name) + "' (type " + shown(f.type) + ") is unknown or nests too deep (corrupt)");
        }
        one = *inner;
      }
      offset += one * f.count;
    }
    return std::nullopt;
  }

  static bool numeric(const Slot& s) { return s.base != Base::nested && s.base != Base::character; }

  // How to decode the asked topic's data messages, from its format.
  Layout layout(const std::vector<Field>& fields, ByteCursor& m) const {
    Layout l;
    auto need = [&](std::string_view name) {
      const auto s = slot(fields, name, m);
      if (!s || !numeric(*s)) {
        refuse(m, fmt::format("the format of {} has no numeric field '{}' (a PX4 version whose layout this reader "
                              "does not know); fix: read another IMU topic of the log (sensor_combined, vehicle_imu, "
                              "sensor_gyro, sensor_accel)", topic_, name));
      }
      return *s;
    };
    auto three = [&](std::string_view array, std::string_view x) {
      // A [3] array, or scalars x, y, z that follow each other.
      if (const auto s = slot(fields, array, m); s && s->count == 3 && numeric(*s)) return *s;
      Slot sx = need(x);
      const Slot sy = need(std::string(x.substr(0, x.size() - 1)) + "y");
      const Slot sz = need(std::string(x.substr(0, x.size() - 1)) + "z");
      if (sy.base != sx.base || sz.base != sx.base || sy.offset != sx.offset + size_of(sx.base) ||
          sz.offset != sy.offset + size_of(sx.base)) {
        refuse(m, "fields x, y, z of " + topic_ + " are not consecutive values of one type (an unknown layout); "
                  "fix: read another IMU topic of the log");
      }
      sx.count = 3;
      return sx;
    };
    const auto sample = slot(fields, "timestamp_sample", m);
    l.time = sample && sample->base == Base::u64 ? *sample : need("timestamp");
    if (l.time.base != Base::u64) m.fail("timestamp of " + topic_ + " is not uint64_t (corrupt)");
    if (topic_ == "sensor_combined") {
      l.vectors.push_back({Quantity::gyro, three("gyro_rad", "gyro_rad"), std::nullopt, std::nullopt});
      Vector3 a{Quantity::accel, three("accelerometer_m_s2", "accelerometer_m_s2"), std::nullopt, std::nullopt};
      if (const auto r = slot(fields, "accelerometer_timestamp_relative", m); r && r->base == Base::i32) a.relative = *r;
      l.vectors.push_back(a);
    } else if (topic_ == "vehicle_imu") {
      l.vectors.push_back({Quantity::gyro, three("delta_angle", "delta_angle"), need("delta_angle_dt"), std::nullopt});
      l.vectors.push_back({Quantity::accel, three("delta_velocity", "delta_velocity"), need("delta_velocity_dt"), std::nullopt});
    } else if (topic_ == "vehicle_angular_velocity" || topic_ == "sensor_gyro") {
      l.vectors.push_back({Quantity::gyro, three("xyz", "x"), std::nullopt, std::nullopt});
    } else {
      l.vectors.push_back({Quantity::accel, three("xyz", "x"), std::nullopt, std::nullopt});
    }
    l.needed = l.time.end();
    for (const auto& v : l.vectors) {
      l.needed = std::max(l.needed, v.value.end());
      if (v.dt_us) l.needed = std::max(l.needed, v.dt_us->end());
      if (v.relative) l.needed = std::max(l.needed, v.relative->end());
    }
    return l;
  }

  void subscribe(ByteCursor& m) {
    const std::uint8_t multi_id = m.u8("multi_id");
    const std::uint16_t id = m.u16("msg_id");
    const std::string name(m.text(m.remaining(), "message name"));
    topics_[name].instances.insert(multi_id);
    name_of_[id] = name;
    decoder_[id] = nullptr;
    if (name != topic_ || !is_imu_topic(name)) return;
    const auto f = formats_.find(name);
    if (f == formats_.end()) m.fail("subscription to " + shown(name) + " without its format ('F') message (corrupt)");
    if (!layout_) layout_ = layout(f->second, m);
    decoder_[id] = &instances_[multi_id];
  }

  void data(std::span<const unsigned char> body, std::size_t at) {
    if (body.size() < 2) {
      throw InputError(fmt::format("{}: byte {}: data ('D') message of {} bytes has no msg_id (corrupt); fix: the log "
                                   "is corrupt or was cut short: copy it again", source_, at, body.size()));
    }
    const std::uint16_t id = static_cast<std::uint16_t>(body[0] | (body[1] << 8));
    ++counts_[id];
    Instance* const instance = decoder_[id];
    if (instance == nullptr) return;
    const unsigned char* p = body.data() + 2;
    if (body.size() - 2 < layout_->needed) {
      throw InputError(fmt::format("{}: byte {}: {} data message of {} bytes is shorter than its format's fields ({} "
                                   "bytes); fix: the log is corrupt, copy it again",
                                   source_, at, topic_, body.size() - 2, layout_->needed));
    }
    const std::uint64_t time_us = u64_at(p + layout_->time.offset);
    if (time_us > std::uint64_t{std::numeric_limits<std::int64_t>::max()} / 1000) {
      throw InputError(fmt::format("{}: byte {}: {} timestamp {} µs is beyond the year 2262; fix: the log is "
                                   "corrupt, copy it again", source_, at,
                                   topic_, time_us));
    }
    const auto time_ns = static_cast<std::int64_t>(time_us) * 1000;
    auto& series = instance->series;
    for (std::size_t k = 0; k < layout_->vectors.size(); ++k) {
      const Vector3& v = layout_->vectors[k];
      std::int64_t t = time_ns;
      if (v.relative) {
        const double rel = value_at(p + v.relative->offset, Base::i32);
        // INT32_MAX marks "no accelerometer data in this message" (RELATIVE_TIMESTAMP_INVALID).
        if (rel == std::numeric_limits<std::int32_t>::max()) continue;
        t += static_cast<std::int64_t>(rel) * 1000;
      }
      double scale = 1.0;
      if (v.dt_us) {
        const double dt = value_at(p + v.dt_us->offset, v.dt_us->base);
        if (!(dt > 0)) {
          throw InputError(fmt::format("{}: byte {}: {} message with an integration interval of {} µs; "
                                       "fix: the log is corrupt, or read sensor_gyro/sensor_accel instead",
                                       source_, at, topic_, dt));
        }
        scale = 1e6 / dt;
      }
      Series& s = series[k];
      s.stamp_ns.push_back(t);
      const std::size_t step = size_of(v.value.base);
      for (std::size_t i = 0; i < 3; ++i) s.v[i].push_back(value_at(p + v.value.offset + i * step, v.value.base) * scale);
    }
  }

  static bool is_imu_topic(std::string_view name) {
    return std::find(std::begin(kImuTopics), std::end(kImuTopics), name) != std::end(kImuTopics);
  }

  std::string listing() const {
    std::vector<StreamInfo> streams;
    std::map<std::string, std::uint64_t> counts;
    for (const auto& [id, name] : name_of_) counts[name] += counts_[id];
    for (const auto& [name, t] : topics_) {
      std::string instances;
      for (const auto i : t.instances) instances += (instances.empty() ? "" : ",") + std::to_string(i);
      streams.push_back({shown(name), (is_imu_topic(name) ? "IMU, multi_id " : "multi_id ") + instances, counts[name]});
    }
    return describe_streams(streams, "topic");
  }

  Recording recording() {
    if (instances_.empty()) {
      std::string readable;
      for (const auto t : kImuTopics) {
        if (topics_.contains(std::string(t))) readable += (readable.empty() ? "" : ", ") + std::string(t);
      }
      const std::string fix = readable.empty()
          ? "this log has none of the IMU topics read (sensor_combined, vehicle_imu, vehicle_angular_velocity, "
            "vehicle_acceleration, sensor_gyro, sensor_accel); enable one in the PX4 logger profile"
          : "pass --topic with one of " + readable;
      std::string what = "no topic " + topic_;
      if (topic_.empty()) what = "no --topic given";
      else if (topics_.contains(topic_)) what = "topic " + topic_ + " is not an IMU topic this reader knows";
      throw InputError(source_ + ": " + what + "; fix: " + fix + "; topics in the log:\n" + listing());
    }
    // Channels: gyro then accel, instance by instance; one instance: gyro_x..accel_z.
    const bool several = instances_.size() > 1 || instances_.begin()->first != 0;
    std::int64_t origin = std::numeric_limits<std::int64_t>::max();
    for (const auto& [multi_id, instance] : instances_) {
      for (const auto& s : instance.series) {
        if (!s.stamp_ns.empty()) origin = std::min(origin, s.stamp_ns.front());
      }
    }
    if (origin == std::numeric_limits<std::int64_t>::max()) {
      throw InputError(source_ + ": topic " + topic_ + " has no messages; fix: choose a topic that has some:\n" + listing());
    }
    Recording r;
    r.source = source_;
    r.format = RecordingFormat::ulog;
    r.stream = topic_;
    r.message_type = "px4/" + topic_;
    r.time_origin = fmt::format("{} ns", origin);
    std::vector<const std::vector<std::int64_t>*> stamps;
    for (auto& [multi_id, instance] : instances_) {
      for (std::size_t k = 0; k < layout_->vectors.size(); ++k) {
        Series& s = instance.series[k];
        if (s.stamp_ns.empty()) continue;
        const bool gyro = layout_->vectors[k].quantity == Quantity::gyro;
        const std::string prefix = std::string(gyro ? "gyro" : "accel") + (several ? std::to_string(multi_id) : "");
        for (int i = 0; i < 3; ++i) {
          r.channels.push_back(Channel{prefix + "_" + "xyz"[i], parse_unit(gyro ? "rad/s" : "m/s^2"), std::move(s.v[i])});
          stamps.push_back(&s.stamp_ns);
        }
      }
    }
    // One time axis for all channels when they share it; else each channel keeps its own.
    const bool shared = std::all_of(stamps.begin(), stamps.end(), [&](const auto* s) { return *s == *stamps.front(); });
    auto seconds = [origin](const std::vector<std::int64_t>& ns) {
      std::vector<double> out(ns.size());
      for (std::size_t i = 0; i < ns.size(); ++i) out[i] = static_cast<double>(ns[i] - origin) * 1e-9;
      return out;
    };
    if (shared) {
      r.time_s = seconds(*stamps.front());
    } else {
      for (std::size_t c = 0; c < r.channels.size(); ++c) r.channels[c].time_s = seconds(*stamps[c]);
    }
    if (dropouts_ > 0) {
      r.notes.push_back(fmt::format("{}: the PX4 logger dropped data {} time{} ({} ms in all); a sample of {} lost "
                                    "there shows as a timestamp gap",
                                    source_, dropouts_, dropouts_ == 1 ? "" : "s", dropout_ms_, topic_));
    }
    return r;
  }

  struct TopicSeen {
    std::set<std::uint8_t> instances;
  };
  struct Instance {
    std::array<Series, 2> series;  // gyro and accel, or the one vector of the topic
  };

  std::span<const unsigned char> bytes_;
  std::string source_;
  std::string topic_;
  std::map<std::string, std::vector<Field>> formats_;
  mutable std::map<std::string, std::optional<std::size_t>> sizes_;  // format_size's memo
  std::map<std::string, TopicSeen> topics_;
  std::map<std::uint16_t, std::string> name_of_;                   // msg_id -> topic
  std::map<std::uint8_t, Instance> instances_;                     // of the asked topic, by multi_id
  std::vector<Instance*> decoder_ = std::vector<Instance*>(65536, nullptr);  // msg_id -> its instance
  std::vector<std::uint64_t> counts_ = std::vector<std::uint64_t>(65536, 0);
  std::optional<Layout> layout_;
  std::vector<std::size_t> appended_;  // file offsets of appended data, sorted
  std::uint64_t dropouts_ = 0;
  std::uint64_t dropout_ms_ = 0;
};

}  // namespace

Recording read_ulog_buffer(std::span<const unsigned char> bytes, std::string_view source, std::string_view topic) {
  return UlogReader(bytes, std::string(source), std::string(topic)).read();
}

Recording read_ulog(const std::filesystem::path& path, std::string_view topic) {
  const MappedFile file(path);
  return read_ulog_buffer(file.bytes(), path.string(), topic);
}

}  // namespace imunoise::io
