// ROS 2 bags in SQLite3 storage (rosbag2_storage_default_plugins' sqlite3 plugin): a bag
// directory holds metadata.yaml and one or more .db3 databases, each with the tables
// topics(id, name, type, serialization_format, ...) and messages(id, topic_id, timestamp,
// data); `data` is the serialized message (CDR for sensor_msgs/msg/Imu, decoded by the MCAP
// reader's decoder). The database is opened read-only and, when no write-ahead log is beside
// it, immutable: SQLite then takes no lock and writes nothing next to the user's file.
//
// Messages are read in rowid ranges on several connections at once (a range scan of the
// table's B-tree each), then concatenated in rowid order, which is the order they were written.
// A bag recorded with --compression-mode message holds each message as one zstd frame (with its
// content size): decompressed before decoding.
#include <sqlite3.h>
#include <zstd.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/core.h>

#include "byte_cursor.hpp"
#include "imunoise/io/imu_containers.hpp"

namespace imunoise::io {
namespace {

namespace fs = std::filesystem;

// "file:" URI of a path (percent-encoding what a URI would misread).
std::string file_uri(const fs::path& path, bool immutable) {
  std::string out = "file:";
  for (const unsigned char ch : fs::absolute(path).string()) {
    if (ch == '%' || ch == '?' || ch == '#' || ch < 0x20 || ch >= 0x7f) out += fmt::format("%{:02X}", ch);
    else out += static_cast<char>(ch);
  }
  return out + (immutable ? "?immutable=1" : "?mode=ro");
}

struct CloseDb {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct FinalizeStatement {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Db = std::unique_ptr<sqlite3, CloseDb>;
using Statement = std::unique_ptr<sqlite3_stmt, FinalizeStatement>;

class Database {
 public:
  explicit Database(const fs::path& path) : source_(path.string()) {
    if (!fs::is_regular_file(path)) throw InputError(source_ + ": no such database file; check the path");
    // A bag being recorded (or left by a crash) may have a write-ahead log: read it too.
    const bool wal = fs::exists(path.string() + "-wal");
    sqlite3* raw = nullptr;
    const int rc = sqlite3_open_v2(file_uri(path, !wal).c_str(), &raw,
                                   SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_NOMUTEX, nullptr);
    db_.reset(raw);
    if (rc != SQLITE_OK) {
      throw InputError(source_ + ": cannot open the database: " + error() + "; fix: check the path and permissions");
    }
    // Read pages straight from the mapped file rather than copying them into SQLite's cache.
    sqlite3_exec(db_.get(), "PRAGMA mmap_size=1099511627776", nullptr, nullptr, nullptr);
  }

  Statement prepare(const char* sql) const {
    sqlite3_stmt* raw = nullptr;
    const int rc = sqlite3_prepare_v2(db_.get(), sql, -1, &raw, nullptr);
    Statement s(raw);
    if (rc == SQLITE_NOTADB) {
      throw InputError(source_ + ": not an SQLite database (so not a ROS 2 .db3 bag); fix: give the bag directory "
                       "or its .db3 file");
    }
    if (rc != SQLITE_OK) {
      const std::string e = error();
      if (e.find("no such table") != std::string::npos || e.find("no such column") != std::string::npos) {
        throw InputError(source_ + ": an SQLite database, but not a ROS 2 bag (" + e +
                         "; a bag has tables topics and messages); fix: give a rosbag2 .db3 file");
      }
      throw InputError(source_ + ": cannot query the database: " + e +
                       "; fix: the file is corrupt or cut short: copy it again (or 'sqlite3 FILE .recover')");
    }
    return s;
  }
  // Steps a statement: true for a row, false at the end; InputError on an error (corruption).
  bool step(sqlite3_stmt* s) const {
    const int rc = sqlite3_step(s);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw InputError(source_ + ": reading the database failed: " + error() +
                     "; fix: the file is corrupt or cut short: copy it again (or 'sqlite3 FILE .recover')");
  }
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  [[nodiscard]] std::string error() const { return db_ ? sqlite3_errmsg(db_.get()) : "out of memory"; }
  std::string source_;
  Db db_;
};

std::string column_text(sqlite3_stmt* s, int i) {
  const unsigned char* t = sqlite3_column_text(s, i);
  return t == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(t));
}

struct TopicRow {
  std::int64_t id = 0;
  std::string name;
  std::string type;
  std::string format;
};

std::vector<TopicRow> topics_of(const Database& db) {
  std::vector<TopicRow> out;
  const Statement s = db.prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY name");
  while (db.step(s.get())) {
    out.push_back({sqlite3_column_int64(s.get(), 0), column_text(s.get(), 1), column_text(s.get(), 2), column_text(s.get(), 3)});
  }
  return out;
}

// Messages per topic id (a scan of the messages table: only for the message listing them).
std::map<std::int64_t, std::uint64_t> counts_of(const Database& db) {
  std::map<std::int64_t, std::uint64_t> out;
  const Statement s = db.prepare("SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id");
  while (db.step(s.get())) out[sqlite3_column_int64(s.get(), 0)] += static_cast<std::uint64_t>(sqlite3_column_int64(s.get(), 1));
  return out;
}

// The Imu messages of topic `id` in the rowid range [first, last], decoded into `out`;
// max_rows bounds the reservation (row ids come from the file: a corrupt range must not
// reserve more than the file could hold).
void read_range(const fs::path& path, std::int64_t id, std::int64_t first, std::int64_t last, std::uint64_t max_rows,
                detail::ImuColumns& out) {
  const Database db(path);
  const Statement s = db.prepare("SELECT id, data FROM messages WHERE id BETWEEN ?1 AND ?2 AND topic_id = ?3");
  sqlite3_bind_int64(s.get(), 1, first);
  sqlite3_bind_int64(s.get(), 2, last);
  sqlite3_bind_int64(s.get(), 3, id);
  // The range's rows bound its Imu messages: reserving them spares the columns their regrowth
  // (a fifth of the read's time before).
  const std::uint64_t rows = static_cast<std::uint64_t>(last) - static_cast<std::uint64_t>(first) + 1;
  out.reserve(static_cast<std::size_t>(std::min(rows, max_rows)));
  detail::ImuSample sample;
  std::string error;
  detail::Bytes plain;
  while (db.step(s.get())) {
    const auto* data = static_cast<const unsigned char*>(sqlite3_column_blob(s.get(), 1));
    std::span<const unsigned char> message{data, data == nullptr ? 0 : static_cast<std::size_t>(sqlite3_column_bytes(s.get(), 1))};
    if (message.size() >= 4 && data[0] == 0x28 && data[1] == 0xB5 && data[2] == 0x2F && data[3] == 0xFD) {
      const std::string where = fmt::format("{}: message {} (zstd)", db.source(), sqlite3_column_int64(s.get(), 0));
      const unsigned long long n = ZSTD_getFrameContentSize(message.data(), message.size());
      if (n == ZSTD_CONTENTSIZE_ERROR || n == ZSTD_CONTENTSIZE_UNKNOWN) {
        throw InputError(where + ": the zstd frame does not state its size; fix: decompress the bag first: "
                         "ros2 bag decompress");
      }
      detail::decompress_zstd(message, n, where, plain);
      message = plain.span();
    }
    if (!detail::decode_cdr_imu(message, sample, error)) {
      throw InputError(fmt::format("{}: message {} ({} bytes): {}; fix: the bag is corrupt, copy it again",
                                   db.source(), sqlite3_column_int64(s.get(), 0), message.size(), error));
    }
    out.push(sample);
  }
}

// The .db3 files of a bag directory, in the order metadata.yaml lists them (relative_file_paths),
// else by name; a bag in another storage (mcap) is refused here and read by the caller.
struct BagFiles {
  std::vector<fs::path> files;
  std::string storage;      // metadata.yaml's storage_identifier ("" when absent)
  std::string compression;  // compression_mode ("" or "none" when not compressed)
};

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.remove_suffix(1);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) s = s.substr(1, s.size() - 2);
  return s;
}

BagFiles bag_files(const fs::path& dir) {
  BagFiles out;
  std::ifstream in(dir / "metadata.yaml");
  std::string line;
  bool in_list = false;
  while (std::getline(in, line)) {
    const std::string_view l = trimmed(line);
    if (in_list && l.starts_with("- ")) {
      out.files.push_back(dir / std::string(trimmed(l.substr(2))));
      continue;
    }
    in_list = l == "relative_file_paths:";
    if (l.starts_with("storage_identifier:")) out.storage = std::string(trimmed(l.substr(19)));
    if (l.starts_with("compression_mode:")) out.compression = std::string(trimmed(l.substr(17)));
  }
  if (out.files.empty()) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const auto ext = entry.path().extension();
      if (ext == ".db3" || ext == ".mcap") out.files.push_back(entry.path());
    }
    std::sort(out.files.begin(), out.files.end());
  }
  return out;
}

}  // namespace

Recording read_ros2_db3(const std::filesystem::path& path, std::string_view topic) {
  const std::string source = path.string();
  std::vector<fs::path> files{path};
  if (fs::is_directory(path)) {
    if (!fs::exists(path / "metadata.yaml")) {
      throw InputError(source + ": a directory without metadata.yaml, so not a ROS 2 bag; fix: give the bag "
                       "directory or a file");
    }
    const BagFiles bag = bag_files(path);
    // Compressed messages are read (zstd frames); compressed files (.db3.zstd) are not.
    std::string mode = bag.compression;
    std::transform(mode.begin(), mode.end(), mode.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (!mode.empty() && mode != "none" && mode != "message") {
      throw InputError(source + ": the bag's files are compressed (compression_mode " + bag.compression +
                       "); fix: decompress it first: ros2 bag decompress");
    }
    if (bag.files.empty()) {
      throw InputError(source + ": metadata.yaml lists no bag files and the directory has no .db3 file; fix: give "
                       "the directory the bag was recorded into");
    }
    if (bag.storage == "mcap" || bag.files.front().extension() == ".mcap") {
      if (bag.files.size() != 1) {
        throw InputError(fmt::format("{}: a bag split into {} MCAP files; fix: give one of them (or merge them with "
                                     "'mcap merge')", source, bag.files.size()));
      }
      return read_mcap(bag.files.front(), topic);
    }
    files = bag.files;
  }
  detail::ImuColumns columns;
  std::string type = "sensor_msgs/msg/Imu";
  std::string missing;  // the first file's refusal, when no file has the topic
  bool found = false;
  for (const auto& file : files) {
    const Database db(file);
    const std::vector<TopicRow> topics = topics_of(db);
    const auto it = std::find_if(topics.begin(), topics.end(), [&](const auto& t) { return t.name == topic; });
    auto listing = [&] {
      const auto counts = counts_of(db);
      std::vector<StreamInfo> streams;
      for (const auto& t : topics) streams.push_back({t.name, t.type, counts.contains(t.id) ? counts.at(t.id) : 0});
      return describe_streams(streams, "topic");
    };
    if (it == topics.end()) {
      // A topic created after a split is not in the earlier files: only a topic in no file is missing.
      if (missing.empty()) {
        missing = file.string() + ": " + (topic.empty() ? std::string("no --topic given") : "no topic " + std::string(topic)) +
                  "; fix: pass --topic with one of the sensor_msgs/msg/Imu topics the bag holds:\n" + listing();
      }
      continue;
    }
    found = true;
    if (it->type != "sensor_msgs/msg/Imu" || it->format != "cdr") {
      throw InputError(file.string() + ": topic " + it->name + " has type " + it->type + " (" + it->format +
                       "), not sensor_msgs/msg/Imu (cdr); fix: pass --topic with an Imu topic; topics in the bag:\n" + listing());
    }
    const Statement range = db.prepare("SELECT MIN(id), MAX(id) FROM messages");
    if (!db.step(range.get()) || sqlite3_column_type(range.get(), 0) == SQLITE_NULL) continue;  // no messages
    const std::int64_t first = sqlite3_column_int64(range.get(), 0);
    const std::int64_t last = sqlite3_column_int64(range.get(), 1);
    // Ranges of ~64 k rows (~25 MB of Imu messages): enough to share among the threads, few
    // enough that opening a connection for each costs nothing.
    // Row ids come from the file: bound the parts and the reservation by its size (a row of
    // an Imu message takes > 300 bytes), so sparse or corrupt ids cannot cost much.
    const std::uint64_t span = static_cast<std::uint64_t>(last) - static_cast<std::uint64_t>(first) + 1;
    const std::uint64_t bytes = fs::file_size(file);
    constexpr std::uint64_t kRows = 1 << 16;
    const std::size_t parts = static_cast<std::size_t>(std::min((span + kRows - 1) / kRows, bytes / (1 << 20) + 1));
    const std::uint64_t per = span / parts + (span % parts != 0);
    columns.reserve(columns.stamp_ns.size() + static_cast<std::size_t>(std::min(span, bytes / 256)));
    detail::decode_chunks(parts, columns, [&](std::size_t k, detail::ImuColumns& part) {
      const auto lo = static_cast<std::int64_t>(static_cast<std::uint64_t>(first) + k * per);
      const auto hi = static_cast<std::int64_t>(std::min<std::uint64_t>(static_cast<std::uint64_t>(first) + (k + 1) * per - 1,
                                                                        static_cast<std::uint64_t>(last)));
      read_range(file, it->id, lo, hi, bytes / 256, part);
    });
  }
  if (!found) throw InputError(missing);
  return detail::imu_recording(std::move(columns), source, RecordingFormat::ros2_db3, std::string(topic), type);
}

}  // namespace imunoise::io
