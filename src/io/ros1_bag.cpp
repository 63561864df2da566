// ROS 1 bag v2.0 (http://wiki.ros.org/Bags/Format/2.0), read without rosbag_storage.
//
// A bag is "#ROSBAG V2.0\n" then records: uint32 header length, header (uint32-length-prefixed
// "name=value" fields, "op" says the record kind), uint32 data length, data. Messages (op 2)
// live inside chunks (op 5; compression none, bz2 or lz4), each preceded in its chunk by the
// connection record (op 7) of its topic. After the chunks, at the bag header's index_pos, come
// every connection record and one chunk info (op 6) per chunk listing the connections in it
// and their message counts: when present, those give the topics with their counts without
// decompressing anything, and let chunks holding no IMU message be skipped. A bag whose
// recording was interrupted has index_pos 0 and is scanned linearly.
#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include <fmt/core.h>

#include "byte_cursor.hpp"
#include "imunoise/io/imu_containers.hpp"

namespace imunoise::io {
namespace {

using detail::ByteCursor;

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
constexpr std::string_view kImuType = "sensor_msgs/Imu";

enum Op : std::uint8_t { kMessage = 2, kBagHeader = 3, kIndex = 4, kChunk = 5, kChunkInfo = 6, kConnection = 7 };

// The fields of a record header that the reader uses.
struct Fields {
  std::optional<std::uint8_t> op;
  std::optional<std::uint32_t> conn;
  std::optional<std::uint64_t> index_pos;
  std::optional<std::uint64_t> chunk_pos;
  std::optional<std::uint32_t> size;
  std::string_view compression;
  std::string_view topic;
  std::string_view type;
};

template <class T>
T field_int(ByteCursor& c, std::string_view value, std::string_view name) {
  if (value.size() != sizeof(T)) {
    c.fail("header field '" + std::string(name) + "' has " + std::to_string(value.size()) +
           " bytes, expected " + std::to_string(sizeof(T)));
  }
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(T{static_cast<unsigned char>(value[i])} << (8 * i));
  return v;
}

// Parses "name=value" fields of `len` bytes at the cursor.
Fields parse_fields(ByteCursor& c, std::uint32_t len) {
  Fields f;
  const std::size_t end = c.pos() + len;
  if (len > c.remaining()) c.fail("record header of " + std::to_string(len) + " bytes runs past the end (truncated or corrupt)");
  while (c.pos() < end) {
    const std::uint32_t flen = c.u32("header field length");
    if (flen > end - c.pos()) c.fail("header field of " + std::to_string(flen) + " bytes runs past its record header (corrupt)");
    const std::string_view field = c.text(flen, "header field");
    const auto eq = field.find('=');
    if (eq == std::string_view::npos) c.fail("header field without '=' (corrupt)");
    const std::string_view name = field.substr(0, eq);
    const std::string_view value = field.substr(eq + 1);
    if (name == "op") f.op = field_int<std::uint8_t>(c, value, name);
    else if (name == "conn") f.conn = field_int<std::uint32_t>(c, value, name);
    else if (name == "index_pos") f.index_pos = field_int<std::uint64_t>(c, value, name);
    else if (name == "chunk_pos") f.chunk_pos = field_int<std::uint64_t>(c, value, name);
    else if (name == "size") f.size = field_int<std::uint32_t>(c, value, name);
    else if (name == "compression") f.compression = value;
    else if (name == "topic") f.topic = value;
    else if (name == "type") f.type = value;
  }
  return f;
}

struct Record {
  Fields fields;
  std::span<const unsigned char> data;
  std::size_t offset = 0;  // of the record in its buffer
};

// Reads the record at the cursor (header, then data).
Record next_record(ByteCursor& c) {
  Record r;
  r.offset = c.pos();
  const std::uint32_t hlen = c.u32("record header length");
  r.fields = parse_fields(c, hlen);
  if (!r.fields.op) c.fail("record header without an 'op' field (corrupt)");
  const std::uint32_t dlen = c.u32("record data length");
  r.data = c.take(dlen, "record data");
  return r;
}

struct Connection {
  std::string topic;
  std::string type;
  std::uint64_t count = 0;
};

class BagReader {
 public:
  BagReader(std::span<const unsigned char> bytes, std::string source, std::string topic)
      : bytes_(bytes), source_(std::move(source)), topic_(std::move(topic)) {}

  Recording read() {
    ByteCursor c(bytes_, source_);
    const std::string_view magic = c.text(std::min(kMagic.size(), c.remaining()), "magic");
    if (magic != kMagic) {
      throw InputError(source_ + ": not a ROS bag v2.0 file (it starts with '" + printable(magic) +
                       "'); fix: give a bag v2.0 file (migrate older bags with 'rosbag fix')");
    }
    const Record header = next_record(c);
    if (*header.fields.op != kBagHeader) c.fail("expected the bag header record (op 3) after the magic");
    const std::uint64_t index_pos = header.fields.index_pos.value_or(0);
    const std::size_t first_record = c.pos();
    if (index_pos != 0 && read_index(index_pos)) {
      select_connections();
      // Chunks are independent: decompress and decode them in parallel, concatenate in order.
      detail::decode_chunks(chunks_.size(), columns_, [&](std::size_t k, detail::ImuColumns& part) {
        ByteCursor cc(bytes_, source_);
        cc.seek(chunks_[k], "chunk_pos of a chunk info");
        const Record chunk = next_record(cc);
        if (*chunk.fields.op != kChunk) cc.fail("chunk_pos does not point at a chunk record (corrupt index)");
        read_chunk(chunk, chunks_[k], false, part);
      });
    } else {
      connections_.clear();
      scan(first_record);
    }
    return finish();
  }

 private:
  static std::string printable(std::string_view s) {
    std::string out;
    for (char ch : s.substr(0, 16)) out += (ch >= 32 && ch < 127) ? ch : '?';
    return out;
  }

  void add_connection(const Record& r, const ByteCursor& c) {
    if (!r.fields.conn) c.fail("connection record without 'conn' (corrupt)");
    auto& conn = connections_[*r.fields.conn];
    // The data is a header too: topic, type, md5sum, message_definition, ...
    ByteCursor d(r.data, c.where() + " (connection record)");
    const Fields f = parse_fields(d, static_cast<std::uint32_t>(r.data.size()));
    conn.topic = std::string(r.fields.topic.empty() ? f.topic : r.fields.topic);
    conn.type = std::string(f.type);
  }

  // The index section: connection records and chunk infos. Returns false if index_pos is past
  // the end (the bag was not closed properly), so that the caller scans instead.
  bool read_index(std::uint64_t index_pos) {
    if (index_pos >= bytes_.size()) return false;
    ByteCursor c(bytes_, source_);
    c.seek(static_cast<std::size_t>(index_pos), "index_pos");
    while (!c.at_end()) {
      const Record r = next_record(c);
      if (*r.fields.op == kConnection) {
        add_connection(r, c);
      } else if (*r.fields.op == kChunkInfo) {
        if (!r.fields.chunk_pos) c.fail("chunk info without 'chunk_pos' (corrupt)");
        ByteCursor d(r.data, source_ + " (chunk info)");
        std::vector<std::uint32_t> conns;
        while (!d.at_end()) {
          const std::uint32_t conn = d.u32("chunk info connection");
          const std::uint32_t count = d.u32("chunk info count");
          connections_[conn].count += count;
          conns.push_back(conn);
        }
        chunk_conns_.emplace_back(*r.fields.chunk_pos, std::move(conns));
      } else {
        c.fail("unexpected record (op " + std::to_string(*r.fields.op) + ") in the index section (corrupt)");
      }
    }
    return true;
  }

  // With the index read: which connections are the topic's, and which chunks hold them.
  void select_connections() {
    check_topic();
    for (const auto& [pos, conns] : chunk_conns_) {
      if (std::any_of(conns.begin(), conns.end(), [&](std::uint32_t k) { return wanted_.contains(k); })) {
        chunks_.push_back(static_cast<std::size_t>(pos));
      }
    }
    std::uint64_t total = 0;
    for (const auto k : wanted_) total += connections_[k].count;
    // The counts come from the file: never reserve more than its bytes could hold (an Imu
    // message record is > 300 bytes), so a corrupt count cannot exhaust memory.
    columns_.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(total, bytes_.size() / 256)));
  }

  // The topic must exist and carry sensor_msgs/Imu; otherwise list what the bag holds.
  void check_topic() {
    wanted_.clear();
    std::string other_type;
    for (const auto& [id, conn] : connections_) {
      if (conn.topic != topic_) continue;
      if (conn.type == kImuType) wanted_.insert(id);
      else other_type = conn.type;
    }
    if (!wanted_.empty()) return;
    if (!other_type.empty()) {
      throw InputError(source_ + ": topic " + topic_ + " has type " + other_type + ", not " +
                       std::string(kImuType) + "; fix: pass --topic with a sensor_msgs/Imu topic; topics in the file:\n" + listing());
    }
    throw InputError(source_ + ": " + (topic_.empty() ? std::string("no --topic given") : "no topic " + topic_) +
                     "; fix: pass --topic with one of the sensor_msgs/Imu topics the file holds:\n" + listing());
  }

  std::string listing() const {
    std::map<std::pair<std::string, std::string>, std::uint64_t> topics;
    for (const auto& [id, conn] : connections_) topics[{conn.topic, conn.type}] += conn.count;
    std::vector<StreamInfo> streams;
    for (const auto& [key, count] : topics) streams.push_back({key.first, key.second, count});
    return describe_streams(streams, "topic");
  }

  // Linear scan from the first record after the bag header (unindexed bags).
  void scan(std::size_t first) {
    ByteCursor c(bytes_, source_);
    c.seek(first, "first record");
    counting_ = true;
    while (!c.at_end()) {
      const std::size_t at = c.pos();
      const Record r = next_record(c);
      if (*r.fields.op == kChunk) read_chunk(r, at, true, columns_);
      else if (*r.fields.op == kConnection) add_connection(r, c);
      else if (*r.fields.op == kMessage) message(r, c, columns_);
    }
    check_topic();
  }

  void read_chunk(const Record& chunk, std::size_t file_offset, bool scanning, detail::ImuColumns& out) {
    const std::string where = source_ + ": chunk at byte " + std::to_string(file_offset);
    if (!chunk.fields.size) throw InputError(where + ": chunk without 'size'; fix: the file is corrupt, copy it again");
    detail::Bytes owned = buffers_.take();
    std::span<const unsigned char> data;
    const auto comp = chunk.fields.compression;
    if (comp == "none") {
      data = chunk.data;
      if (data.size() != *chunk.fields.size) {
        throw InputError(where + ": uncompressed chunk of " + std::to_string(data.size()) +
                         " bytes but its header says " + std::to_string(*chunk.fields.size) + "; fix: the file is corrupt, copy it again");
      }
    } else if (comp == "bz2") {
      detail::decompress_bz2(chunk.data, *chunk.fields.size, where, owned);
      data = owned.span();
    } else if (comp == "lz4") {
      detail::decompress_lz4_frame(chunk.data, *chunk.fields.size, where, owned);
      data = owned.span();
    } else {
      throw InputError(where + ": unknown chunk compression '" + printable(comp) +
                       "'; fix: recompress the bag with 'rosbag compress --lz4' (none, bz2 and lz4 are read)");
    }
    ByteCursor c(data, where + " (decompressed)");
    // Upper bound of the Imu messages the chunk can hold (a record takes > 300 bytes): the
    // columns do not regrow, and capacity never touched costs no memory.
    if (!scanning) out.reserve(data.size() / 300 + 1);
    while (!c.at_end()) {
      const Record r = next_record(c);
      if (*r.fields.op == kMessage) message(r, c, out);
      else if (*r.fields.op == kConnection && scanning) add_connection(r, c);
    }
    buffers_.give(std::move(owned));
  }

  void message(const Record& r, const ByteCursor& c, detail::ImuColumns& out) {
    if (!r.fields.conn) c.fail("message record without 'conn' (corrupt)");
    const std::uint32_t conn = *r.fields.conn;
    if (counting_) {
      auto it = connections_.find(conn);
      if (it == connections_.end()) c.fail("message on connection " + std::to_string(conn) + " before its connection record (corrupt)");
      ++it->second.count;
      if (it->second.type != kImuType || it->second.topic != topic_) return;
    } else if (!wanted_.contains(conn)) {
      return;
    }
    detail::ImuSample s;
    if (!detail::decode_ros1_imu(r.data, s)) {
      c.fail("a sensor_msgs/Imu message of " + std::to_string(r.data.size()) + " bytes is too short (corrupt)");
    }
    out.push(s);
  }

  Recording finish() {
    return detail::imu_recording(std::move(columns_), source_, RecordingFormat::ros1_bag, topic_,
                                 std::string(kImuType));
  }

  std::span<const unsigned char> bytes_;
  std::string source_;
  std::string topic_;
  std::map<std::uint32_t, Connection> connections_;
  std::vector<std::pair<std::uint64_t, std::vector<std::uint32_t>>> chunk_conns_;
  std::vector<std::size_t> chunks_;
  std::set<std::uint32_t> wanted_;
  bool counting_ = false;
  detail::ImuColumns columns_;
  detail::BufferPool buffers_;
};

}  // namespace

Recording read_ros1_bag_buffer(std::span<const unsigned char> bytes, std::string_view source,
                               std::string_view topic) {
  return BagReader(bytes, std::string(source), std::string(topic)).read();
}

Recording read_ros1_bag(const std::filesystem::path& path, std::string_view topic) {
  const MappedFile file(path);
  return read_ros1_bag_buffer(file.bytes(), path.string(), topic);
}

}  // namespace imunoise::io
