// ROS 2 MCAP (https://mcap.dev/spec), read without an MCAP library (none is packaged in Debian).
//
// A file is the magic "\x89MCAP0\r\n", records (uint8 opcode, uint64 length, content), and the
// magic again. Messages (opcode 5) sit in chunks (6; compression "", "zstd" or "lz4" frame) or
// loose in the data section; each names a channel (4: topic, message encoding, schema id) whose
// schema (3) names the type. A file closed properly ends with a summary section (pointed to by
// the footer, 2): every schema and channel, statistics (11: message counts per channel) and
// one chunk index (8) per chunk with the channels it holds. When present, the summary gives the
// topic listing without decompressing anything and lets chunks without the IMU channel be
// skipped; otherwise (a writer that crashed, or a summary-less file) the data section is
// scanned linearly. All integers are little-endian.
#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include "byte_cursor.hpp"
#include "imunoise/io/imu_containers.hpp"

namespace imunoise::io {
namespace {

using detail::ByteCursor;

constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
constexpr std::uint64_t kUnknown = std::numeric_limits<std::uint64_t>::max();

enum Op : std::uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kChunkIndex = 0x08, kStatistics = 0x0B, kDataEnd = 0x0F
};

std::string_view str(ByteCursor& c, std::string_view what) {
  const std::uint32_t n = c.u32(what);
  return c.text(n, what);
}

struct Schema {
  std::string name;
  std::string encoding;
};
struct ChannelInfo {
  std::string topic;
  std::string message_encoding;
  std::uint16_t schema_id = 0;
  std::uint64_t count = 0;
};

class McapReader {
 public:
  McapReader(std::span<const unsigned char> bytes, std::string source, std::string topic)
      : bytes_(bytes), source_(std::move(source)), topic_(std::move(topic)) {}

  Recording read() {
    ByteCursor c(bytes_, source_);
    if (c.remaining() < kMagic.size() || c.text(kMagic.size(), "magic") != kMagic) {
      throw InputError(source_ + ": not an MCAP file (no MCAP magic at the start); fix: give an .mcap file");
    }
    if (!read_summary()) {
      channels_.clear();
      schemas_.clear();
      scan();
    }
    return detail::imu_recording(std::move(columns_), source_, RecordingFormat::mcap, topic_, type_);
  }

 private:
  // Record content of `op` at the cursor: returns a cursor over its content.
  struct Rec {
    std::uint8_t op;
    std::span<const unsigned char> content;
    std::size_t offset;
  };
  static Rec next(ByteCursor& c) {
    Rec r{};
    r.offset = c.pos();
    r.op = c.u8("record opcode");
    const std::uint64_t len = c.u64("record length");
    r.content = c.take(len, "record content");
    return r;
  }
  ByteCursor content(const Rec& r, std::string_view kind, std::uint64_t base) const {
    return ByteCursor(r.content, source_ + ": " + std::string(kind) + " record at byte " +
                                     std::to_string(base + r.offset));
  }

  void add_schema(ByteCursor c) {
    const std::uint16_t id = c.u16("schema id");
    Schema s;
    s.name = std::string(str(c, "schema name"));
    s.encoding = std::string(str(c, "schema encoding"));
    schemas_[id] = std::move(s);
  }
  void add_channel(ByteCursor c) {
    const std::uint16_t id = c.u16("channel id");
    ChannelInfo ch;
    ch.schema_id = c.u16("channel schema id");
    ch.topic = std::string(str(c, "channel topic"));
    ch.message_encoding = std::string(str(c, "channel message encoding"));
    auto& slot = channels_[id];
    const std::uint64_t count = slot.count;
    slot = std::move(ch);
    slot.count = count;
  }

  std::string type_of(const ChannelInfo& ch) const {
    if (ch.schema_id == 0) return "(no schema)";
    const auto it = schemas_.find(ch.schema_id);
    return it == schemas_.end() ? "(unknown schema " + std::to_string(ch.schema_id) + ")" : it->second.name;
  }
  // sensor_msgs/msg/Imu in CDR (ROS 2), or sensor_msgs/Imu in ros1 encoding (ROS 1 in MCAP).
  int decoder_of(const ChannelInfo& ch) const {
    const std::string type = type_of(ch);
    if (type == "sensor_msgs/msg/Imu" && ch.message_encoding == "cdr") return 2;
    if (type == "sensor_msgs/Imu" && ch.message_encoding == "ros1") return 1;
    return 0;
  }

  void check_topic() {
    std::string other;
    for (const auto& [id, ch] : channels_) {
      if (ch.topic != topic_) continue;
      if (const int d = decoder_of(ch)) {
        decoder_[id] = d;
        type_ = type_of(ch);
      } else {
        other = type_of(ch) + " (" + ch.message_encoding + ")";
      }
    }
    if (!decoder_.empty()) return;
    if (!other.empty()) {
      throw InputError(source_ + ": topic " + topic_ + " has type " + other +
                       ", not sensor_msgs/msg/Imu (cdr); fix: pass --topic with an Imu topic; topics in the file:\n" + listing());
    }
    throw InputError(source_ + ": " + (topic_.empty() ? std::string("no --topic given") : "no topic " + topic_) +
                     "; fix: pass --topic with one of the sensor_msgs/msg/Imu topics the file holds:\n" + listing());
  }

  std::string listing() const {
    std::vector<StreamInfo> streams;
    for (const auto& [id, ch] : channels_) streams.push_back({ch.topic, type_of(ch), ch.count});
    std::sort(streams.begin(), streams.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    std::string out = describe_streams(streams, "topic");
    if (!counts_known_) {
      // Without statistics the counts were not read; say so rather than print zeros.
      std::string fixed;
      for (const auto& s : streams) fixed += "  " + s.name + "  " + s.type + "\n";
      return fixed.empty() ? out : fixed;
    }
    return out;
  }

  void message(ByteCursor c, detail::ImuColumns& out) {
    const std::uint16_t id = c.u16("message channel id");
    if (scanning_) {
      const auto it = channels_.find(id);
      if (it == channels_.end()) c.fail("message on channel " + std::to_string(id) + " before its channel record (corrupt)");
      ++it->second.count;
      if (it->second.topic != topic_) return;
      if (!decoder_.contains(id)) {
        const int d = decoder_of(it->second);
        if (d == 0) return;
        decoder_[id] = d;
        type_ = type_of(it->second);
      }
    }
    const auto it = decoder_.find(id);
    if (it == decoder_.end()) return;
    c.take(4 + 8 + 8, "message header");
    const auto data = c.take(c.remaining(), "message data");
    detail::ImuSample s;
    std::string error;
    if (it->second == 2 ? !detail::decode_cdr_imu(data, s, error) : !detail::decode_ros1_imu(data, s)) {
      c.fail(error.empty() ? "a sensor_msgs/Imu message is too short (corrupt)" : error);
    }
    out.push(s);
  }

  // A well-formed message of a channel read from the summary, without the cursor that
  // message() builds (its copy of the chunk's name was an allocation per message). Returns
  // false when message() must handle it: another channel, or anything to report.
  bool decode_fast(std::span<const unsigned char> content, detail::ImuColumns& out) const {
    constexpr std::size_t header = 2 + 4 + 8 + 8;  // channel id, sequence, log and publish time
    if (content.size() < header) return false;
    const auto id = static_cast<std::uint16_t>(content[0] | (content[1] << 8));
    const auto it = decoder_.find(id);
    if (it == decoder_.end()) return true;  // another channel: nothing to do
    detail::ImuSample s;
    std::string error;
    const auto data = content.subspan(header);
    if (it->second == 2 ? !detail::decode_cdr_imu(data, s, error) : !detail::decode_ros1_imu(data, s)) return false;
    out.push(s);
    return true;
  }

  void chunk(const Rec& r, std::uint64_t base, detail::ImuColumns& out) {
    ByteCursor c = content(r, "chunk", base);
    c.take(16, "chunk message times");
    const std::uint64_t uncompressed = c.u64("chunk uncompressed size");
    c.u32("chunk crc");
    const std::string compression(str(c, "chunk compression"));
    const std::uint64_t len = c.u64("chunk records length");
    const auto records = c.take(len, "chunk records");
    const std::string where = source_ + ": chunk at byte " + std::to_string(base + r.offset);
    detail::Bytes owned = buffers_.take();
    std::span<const unsigned char> data = records;
    if (compression == "zstd") data = (detail::decompress_zstd(records, uncompressed, where, owned), owned.span());
    else if (compression == "lz4") data = (detail::decompress_lz4_frame(records, uncompressed, where, owned), owned.span());
    else if (!compression.empty()) throw InputError(where + ": unknown chunk compression '" + compression + "'; fix: recompress with 'mcap convert' to zstd or lz4");
    else if (records.size() != uncompressed) throw InputError(where + ": uncompressed chunk size disagrees with its header; fix: the file is corrupt, copy it again");
    ByteCursor inner(data, where + " (decompressed)");
    // Upper bound of the Imu messages a chunk can hold (a CDR Imu record takes > 300 bytes):
    // reserving it spares the columns their regrowth, and untouched capacity costs nothing.
    if (!scanning_) out.reserve(data.size() / 300 + 1);
    while (!inner.at_end()) {
      const Rec m = next(inner);
      if (m.op == kMessage && !scanning_ && decode_fast(m.content, out)) continue;
      if (m.op == kMessage) message(ByteCursor(m.content, inner.where()), out);
      else if (m.op == kSchema && scanning_) add_schema(ByteCursor(m.content, inner.where()));
      else if (m.op == kChannel && scanning_) add_channel(ByteCursor(m.content, inner.where()));
    }
    buffers_.give(std::move(owned));
  }

  // Linear scan of the data section: every record from the header to the data end.
  void scan() {
    scanning_ = true;
    counts_known_ = true;
    ByteCursor c(bytes_, source_);
    c.seek(kMagic.size(), "first record");
    while (!c.at_end()) {
      // A truncated record is reported (naming its byte), never silently dropped.
      const Rec r = next(c);
      if (r.op == kSchema) add_schema(content(r, "schema", 0));
      else if (r.op == kChannel) add_channel(content(r, "channel", 0));
      else if (r.op == kMessage) message(content(r, "message", 0), columns_);
      else if (r.op == kChunk) chunk(r, 0, columns_);
      else if (r.op == kDataEnd || r.op == kFooter) break;
    }
    check_topic();
  }

  // The summary section, when the footer points to one with chunk indexes (or no chunks at
  // all and no loose messages: then the scan is needed anyway). Returns false to scan.
  bool read_summary() {
    constexpr std::size_t footer_bytes = 1 + 8 + 8 + 8 + 4;
    if (bytes_.size() < kMagic.size() * 2 + footer_bytes) return false;
    const std::size_t footer_at = bytes_.size() - kMagic.size() - footer_bytes;
    ByteCursor f(bytes_, source_);
    f.seek(bytes_.size() - kMagic.size(), "end magic");
    if (f.text(kMagic.size(), "end magic") != kMagic) return false;  // truncated: scan
    f.seek(footer_at, "footer");
    if (f.u8("footer opcode") != kFooter || f.u64("footer length") != 20) return false;
    const std::uint64_t summary_start = f.u64("summary start");
    if (summary_start == 0) return false;
    if (summary_start < kMagic.size() || summary_start > footer_at) f.fail("summary_start points outside the file (corrupt)");
    ByteCursor c(bytes_.subspan(0, footer_at), source_);
    c.seek(static_cast<std::size_t>(summary_start), "summary start");
    std::vector<std::pair<std::uint64_t, bool>> chunks;  // offset, holds a wanted channel
    std::vector<std::vector<std::uint16_t>> chunk_channels;
    bool have_stats = false;
    while (!c.at_end()) {
      const Rec r = next(c);
      if (r.op == kSchema) add_schema(content(r, "schema", 0));
      else if (r.op == kChannel) add_channel(content(r, "channel", 0));
      else if (r.op == kStatistics) {
        ByteCursor s = content(r, "statistics", 0);
        s.take(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8, "statistics counts");
        const std::uint32_t len = s.u32("channel message counts length");
        ByteCursor m(s.take(len, "channel message counts"), s.where());
        while (!m.at_end()) {
          const std::uint16_t id = m.u16("channel id");
          stats_counts_[id] = m.u64("message count");
        }
        have_stats = true;
      } else if (r.op == kChunkIndex) {
        ByteCursor s = content(r, "chunk index", 0);
        s.take(16, "chunk index times");
        const std::uint64_t start = s.u64("chunk start offset");
        s.u64("chunk length");
        const std::uint32_t len = s.u32("message index offsets length");
        ByteCursor m(s.take(len, "message index offsets"), s.where());
        std::vector<std::uint16_t> ids;
        while (!m.at_end()) {
          ids.push_back(m.u16("channel id"));
          m.u64("message index offset");
        }
        chunks.emplace_back(start, false);
        chunk_channels.push_back(std::move(ids));
      }
    }
    for (auto& [id, ch] : channels_) ch.count = stats_counts_.contains(id) ? stats_counts_[id] : 0;
    counts_known_ = have_stats;
    if (chunks.empty()) return false;  // messages outside chunks, or none: scan
    check_topic();
    std::uint64_t expected = 0;
    for (const auto& [id, d] : decoder_) expected += stats_counts_.contains(id) ? stats_counts_[id] : 0;
    // Counts come from the file: never reserve more than its bytes could hold (a compressed
    // Imu message still takes > 8 bytes), so a corrupt count cannot exhaust memory.
    columns_.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(expected, bytes_.size() / 8)));
    std::vector<std::size_t> order(chunks.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return chunks[a].first < chunks[b].first; });
    std::vector<Rec> selected;
    for (const auto i : order) {
      // A chunk index without message index offsets says nothing about its channels: read it.
      const auto& ids = chunk_channels[i];
      if (!ids.empty() && std::none_of(ids.begin(), ids.end(), [&](auto id) { return decoder_.contains(id); })) continue;
      ByteCursor cc(bytes_, source_);
      cc.seek(static_cast<std::size_t>(std::min<std::uint64_t>(chunks[i].first, bytes_.size())), "chunk start offset");
      const Rec r = next(cc);
      if (r.op != kChunk) cc.fail("a chunk index points at a record that is not a chunk (corrupt)");
      selected.push_back(r);
    }
    // Chunks are independent: decompress and decode them in parallel (zstd is ~60 % of the
    // time), then concatenate in file order.
    detail::decode_chunks(selected.size(), columns_,
                          [&](std::size_t k, detail::ImuColumns& part) { chunk(selected[k], 0, part); });
    return true;
  }

  std::span<const unsigned char> bytes_;
  std::string source_;
  std::string topic_;
  std::string type_ = "sensor_msgs/msg/Imu";
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, ChannelInfo> channels_;
  std::map<std::uint16_t, std::uint64_t> stats_counts_;
  std::map<std::uint16_t, int> decoder_;
  bool scanning_ = false;
  bool counts_known_ = false;
  detail::ImuColumns columns_;
  detail::BufferPool buffers_;
};

}  // namespace

Recording read_mcap_buffer(std::span<const unsigned char> bytes, std::string_view source, std::string_view topic) {
  return McapReader(bytes, std::string(source), std::string(topic)).read();
}

Recording read_mcap(const std::filesystem::path& path, std::string_view topic) {
  const MappedFile file(path);
  return read_mcap_buffer(file.bytes(), path.string(), topic);
}

}  // namespace imunoise::io
