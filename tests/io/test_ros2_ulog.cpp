// ROS 2 SQLite bags and PX4 ULog logs on files written by independent code: bags by Python's
// sqlite3 module with a CDR writer of the test's own (tests/io/writers/write_db3.py, which saves
// the values it wrote, checked bit for bit), logs by a writer following the published ULog
// specification (tests/io/writers/write_ulog.py), whose values are taken from the reference
// reader @foxglove/ulog (tests/io/ulog_reader, pinned) and must be returned bit for bit. Then
// the refusals: missing or wrong topics (listing what the file holds), truncated and corrupted
// files (an InputError naming the file and, for ULog, the byte; never a crash).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "imunoise/io/imu_containers.hpp"
#include "imunoise/io/recording.hpp"
#include "io_test_support.hpp"

namespace imunoise::io {
namespace {

namespace fs = std::filesystem;
using test::expect_input_error;

const fs::path kTests = fs::path(IMUNOISE_TEST_DATA_DIR).parent_path();
const fs::path kWriters = kTests / "io" / "writers";
const fs::path kUlogReader = kTests / "io" / "ulog_reader";
const fs::path kSampleLog = kTests / "data" / "ulog" / "sample_log_small.ulg";

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool run(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()) == 0; }

RecordingOptions topic(std::string name) {
  RecordingOptions o;
  o.topic = std::move(name);
  return o;
}

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

CliResult run_cli(const std::vector<std::string>& args, const fs::path& dir) {
  std::string command = IMUNOISE_CLI_PATH;
  for (const auto& a : args) command += " '" + a + "'";
  command += " >" + (dir / "out.txt").string() + " 2>" + (dir / "err.txt").string();
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "out.txt"), slurp(dir / "err.txt")};
}

// Files are written on first use and shared by the tests of one process.
class Ros2Ulog : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    have_reference_ = fs::exists(kUlogReader / "node_modules" / "@foxglove" / "ulog") && run("node --version");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  // bag_le, bag_be_split, bag_zstd (directories), log.ulg, relative.ulg, appended.ulg.
  static fs::path file(const std::string& name) {
    const fs::path path = dir_->path() / name;
    if (fs::exists(path)) return path;
    std::string command;
    if (name == "log.ulg") {
      command = "/usr/bin/python3 " + (kWriters / "write_ulog.py").string() + " " + path.string() + " 1500";
    } else if (name == "appended.ulg") {
      command = "/usr/bin/python3 " + (kWriters / "write_ulog.py").string() + " " + path.string() + " 200 5 appended";
    } else if (name == "relative.ulg") {
      command = "/usr/bin/python3 " + (kWriters / "write_ulog.py").string() + " " + path.string() + " 300 9 relative";
    } else {
      const bool big = name.find("be") != std::string::npos;
      const bool split = name.find("split") != std::string::npos;
      const bool zstd = name.find("zstd") != std::string::npos;
      command = "/usr/bin/python3 " + (kWriters / "write_db3.py").string() + " " + path.string() + " 1500 " +
                (big ? "be" : "le") + (split ? " split" : " one") + (zstd ? " 200 zstd" : "");
    }
    if (!run(command)) ADD_FAILURE() << "the writer failed: " << command;
    return path;
  }
  // What @foxglove/ulog reads from `log` for `topic` (see read_ulog.js).
  static nlohmann::json reference(const fs::path& log, const std::string& topic) {
    const fs::path out = dir_->path() / (log.filename().string() + "." + topic + ".json");
    if (!fs::exists(out)) {
      const std::string command = "node " + (kUlogReader / "read_ulog.js").string() + " " + log.string() + " " +
                                  topic + " " + out.string();
      if (!run(command)) ADD_FAILURE() << "the reference reader failed: " << command;
    }
    return nlohmann::json::parse(slurp(out));
  }

  static inline test::TempDir* dir_ = nullptr;
  static inline bool have_reference_ = false;
};

#define REQUIRE_REFERENCE() \
  if (!have_reference_) GTEST_SKIP() << "node_modules missing: run 'npm ci' in tests/io/ulog_reader (.ci/run does)"

// The reader's recording equals the writer's values (float64 rows [t - t0, gx..az]) bit for bit.
void expect_bit_exact(const Recording& r, const fs::path& expected_path, std::size_t n) {
  const std::string bytes = slurp(expected_path);
  std::vector<double> e(bytes.size() / 8);
  std::memcpy(e.data(), bytes.data(), e.size() * 8);
  ASSERT_EQ(e.size(), n * 7);
  ASSERT_EQ(r.sample_count(), n);
  ASSERT_EQ(r.time_s.size(), n);
  const char* names[] = {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"};
  for (std::size_t k = 0; k < 6; ++k) {
    const Channel& c = r.channel(names[k]);
    ASSERT_TRUE(c.unit.has_value());
    EXPECT_EQ(c.unit->name, k < 3 ? "rad/s" : "m/s^2");
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(c.values[i]), std::bit_cast<std::uint64_t>(e[i * 7 + 1 + k]))
          << names[k] << " sample " << i;
    }
  }
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(std::llround(r.time_s[i] * 1e9), std::llround(e[i * 7])) << i;
}

TEST_F(Ros2Ulog, Db3FromPythonSqliteReadsBackBitExactByDirectoryOrFile) {
  const fs::path le = file("bag_le");
  EXPECT_EQ(detect_container(le), RecordingFormat::ros2_db3);
  EXPECT_EQ(detect_container(le / "bag_le_0.db3"), RecordingFormat::ros2_db3);
  for (const fs::path& path : {le, le / "bag_le_0.db3"}) {
    SCOPED_TRACE(path.string());
    const Recording r = read_recording(path, topic("/imu"));
    EXPECT_EQ(r.format, RecordingFormat::ros2_db3);
    EXPECT_EQ(format_name(r.format), "ROS 2 bag (SQLite)");
    EXPECT_EQ(r.stream, "/imu");
    EXPECT_EQ(r.message_type, "sensor_msgs/msg/Imu");
    // header.stamp, not the bag's receive timestamp (which the writer set 0.7-0.8 ms later).
    EXPECT_EQ(r.time_origin, "1700000000987654321 ns");
    expect_bit_exact(r, le / "expected.f64", 1500);
  }
  // Big-endian CDR, messages split between two files in metadata.yaml's order.
  const fs::path be = file("bag_be_split");
  EXPECT_TRUE(fs::exists(be / "bag_be_split_1.db3"));
  expect_bit_exact(read_recording(be, topic("/imu")), be / "expected.f64", 1500);
}

TEST_F(Ros2Ulog, Db3WithZstdCompressedMessagesReadsBackBitExact) {
  // Recorded with --compression-mode message: each message one zstd frame (by the zstd tool).
  const fs::path bag = file("bag_zstd");
  const Recording r = read_recording(bag, topic("/imu"));
  expect_bit_exact(r, bag / "expected.f64", 1500);
  // A corrupt frame is refused naming the message.
  const fs::path db = bag / "bag_zstd_0.db3";
  ASSERT_TRUE(run("/usr/bin/python3 -c \"import sqlite3; d = sqlite3.connect('" + db.string() +
                  "'); d.execute('UPDATE messages SET data = substr(data, 1, 12) || zeroblob(40) WHERE id = 7'); d.commit()\""));
  expect_input_error([&] { (void)read_recording(bag, topic("/imu")); }, {"bag_zstd_0.db3: message 7 (zstd)"});
}

TEST_F(Ros2Ulog, Db3MissingOrWrongTopicListsTopicsWithTypesAndCounts) {
  const fs::path bag = file("bag_le");
  expect_input_error([&] { (void)read_recording(bag, topic("/imu/data")); },
                     {"bag_le_0.db3", "no topic /imu/data", "/imu          sensor_msgs/msg/Imu  1500 messages",
                      "/status       std_msgs/msg/String  3 messages", "/temperature  sensor_msgs/msg/Temperature  5 messages"});
  expect_input_error([&] { (void)read_recording(bag, {}); }, {"no --topic given", "/imu"});
  expect_input_error([&] { (void)read_recording(bag, topic("/temperature")); },
                     {"topic /temperature has type sensor_msgs/msg/Temperature (cdr), not sensor_msgs/msg/Imu"});
  expect_input_error([&] { (void)read_recording(bag, [] { RecordingOptions o; o.topic = "/imu"; o.dataset = "/x"; return o; }()); },
                     {"--dataset applies to HDF5"});
}

TEST_F(Ros2Ulog, Db3ThatIsNotABagIsRefused) {
  test::TempDir dir;
  const fs::path text = dir.write("notes.db3", "this is not a database, just text that is long enough\n");
  expect_input_error([&] { (void)read_recording(text, topic("/imu")); }, {"notes.db3", "not an SQLite database"});
  const fs::path other = dir.path() / "other.db3";
  ASSERT_TRUE(run("/usr/bin/python3 -c \"import sqlite3; d = sqlite3.connect('" + other.string() +
                  "'); d.execute('CREATE TABLE samples(x REAL)'); d.commit()\""));
  EXPECT_EQ(detect_container(other), RecordingFormat::ros2_db3);
  expect_input_error([&] { (void)read_recording(other, topic("/imu")); }, {"other.db3", "not a ROS 2 bag", "no such table"});
  fs::create_directories(dir.path() / "empty_bag");
  EXPECT_FALSE(detect_container(dir.path() / "empty_bag").has_value());  // no metadata.yaml
  std::ofstream(dir.path() / "empty_bag" / "metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: sqlite3\n";
  expect_input_error([&] { (void)read_recording(dir.path() / "empty_bag", topic("/imu")); }, {"no .db3 file"});
  std::ofstream(dir.path() / "empty_bag" / "metadata.yaml") << "  compression_mode: FILE\n";
  expect_input_error([&] { (void)read_recording(dir.path() / "empty_bag", topic("/imu")); },
                     {"compressed", "ros2 bag decompress"});
}

TEST_F(Ros2Ulog, Db3IsReadWithoutWritingAnythingBesideIt) {
  const fs::path bag = file("bag_le");
  const fs::path db = bag / "bag_le_0.db3";
  const std::string before = slurp(db);
  const auto mtime = fs::last_write_time(db);
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(bag)) ++entries;
  (void)read_recording(bag, topic("/imu"));
  EXPECT_THROW((void)read_recording(bag, topic("/nope")), InputError);
  std::size_t after = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(bag)) ++after;
  EXPECT_EQ(after, entries) << "a journal, WAL or lock file was left beside the bag";
  EXPECT_EQ(fs::last_write_time(db), mtime);
  EXPECT_TRUE(slurp(db) == before);
}

TEST_F(Ros2Ulog, Db3TruncatedOrCorruptedIsRefusedOrReadNeverCrash) {
  const std::string bytes = slurp(file("bag_le") / "bag_le_0.db3");
  test::TempDir dir;
  std::mt19937_64 rng(25);
  for (int trial = 0; trial < 30; ++trial) {
    std::string bad = trial < 10 ? bytes.substr(0, bytes.size() * static_cast<std::size_t>(trial) / 10) : bytes;
    for (int k = 0; trial >= 10 && k < 8; ++k) bad[rng() % bad.size()] = static_cast<char>(rng());
    const fs::path path = dir.write("bad.db3", bad);
    try {
      const Recording r = read_recording(path, topic("/imu"));
      EXPECT_LE(r.sample_count(), 1500u);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.db3"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("fix:"), std::string::npos) << e.what();
    }
  }
}

// Row ids come from the file: a bag whose last message id is near 2^62 (ids need not be dense in
// SQLite) must be read like any other, not reserve memory for 2^62 rows (the fuzzer's find:
// std::length_error escaped the reader).
TEST_F(Ros2Ulog, Db3WithSparseHugeRowIdsIsReadWithoutReservingThem) {
  test::TempDir dir;
  const fs::path path = dir.path() / "sparse.db3";
  fs::copy_file(file("bag_le") / "bag_le_0.db3", path);
  const std::string sql = "UPDATE messages SET id = 4611686018427387904 WHERE id = (SELECT MAX(id) FROM messages)";
  ASSERT_TRUE(run("/usr/bin/python3 -c \"import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); c.execute(sys.argv[2]); "
                  "c.commit()\" " + path.string() + " '" + sql + "'"));
  const Recording r = read_recording(path, topic("/imu"));
  EXPECT_EQ(r.sample_count(), 1500u);
}

// Every channel of `r` equals the reference reader's (values bit for bit, times to the ns).
void expect_matches_reference(const Recording& r, const nlohmann::json& reference) {
  const auto& channels = reference.at("channels");
  ASSERT_EQ(r.channels.size(), channels.size()) << r.channel_list();
  const long long origin = std::stoll(r.time_origin);
  for (const Channel& c : r.channels) {
    SCOPED_TRACE(c.name);
    ASSERT_TRUE(channels.contains(c.name)) << r.channel_list();
    const auto& values = channels.at(c.name).at("values");
    const auto& times = channels.at(c.name).at("time_ns");
    const std::vector<double>& t = r.times(c);
    ASSERT_EQ(c.values.size(), values.size());
    ASSERT_EQ(t.size(), times.size());
    ASSERT_TRUE(c.unit.has_value());
    EXPECT_EQ(c.unit->name, c.name.starts_with("gyro") ? "rad/s" : "m/s^2");
    for (std::size_t i = 0; i < values.size(); ++i) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(c.values[i]), std::bit_cast<std::uint64_t>(values[i].get<double>())) << i;
      ASSERT_EQ(origin + std::llround(t[i] * 1e9), std::stoll(times[i].get<std::string>())) << i;
    }
  }
}

TEST_F(Ros2Ulog, UlogEveryImuTopicMatchesTheReferenceReader) {
  REQUIRE_REFERENCE();
  const fs::path log = file("log.ulg");
  EXPECT_EQ(detect_container(log), RecordingFormat::ulog);
  for (const char* t : {"sensor_combined", "sensor_gyro", "sensor_accel", "vehicle_imu", "vehicle_angular_velocity",
                        "vehicle_acceleration"}) {
    SCOPED_TRACE(t);
    const Recording r = read_recording(log, topic(t));
    EXPECT_EQ(r.format, RecordingFormat::ulog);
    EXPECT_EQ(r.stream, t);
    expect_matches_reference(r, reference(log, t));
  }
  // One instance: one time axis, channels without a number; two: numbered, each its own time.
  const Recording combined = read_recording(log, topic("sensor_combined"));
  EXPECT_EQ(combined.channel_list(), "gyro_x, gyro_y, gyro_z, accel_x, accel_y, accel_z");
  EXPECT_EQ(combined.time_s.size(), 1500u);
  const Recording imu = read_recording(log, topic("vehicle_imu"));
  EXPECT_EQ(imu.channel_list(), "gyro0_x, gyro0_y, gyro0_z, accel0_x, accel0_y, accel0_z, "
                                "gyro1_x, gyro1_y, gyro1_z, accel1_x, accel1_y, accel1_z");
  EXPECT_TRUE(imu.time_s.empty());
  EXPECT_EQ(imu.channel("gyro1_y").time_s.size(), 1500u);
  // The dropouts the writer put in (two, 15 + 30 ms) are said.
  const auto written = nlohmann::json::parse(slurp(log.string() + ".json"));
  ASSERT_EQ(written.at("dropouts"), 2);
  ASSERT_EQ(combined.notes.size(), 1u);
  EXPECT_NE(combined.notes[0].find("dropped data 2 times (45 ms in all)"), std::string::npos) << combined.notes[0];
}

TEST_F(Ros2Ulog, UlogSensorCombinedAccelerometerKeepsItsOwnTimeAndSkipsInvalidOnes) {
  REQUIRE_REFERENCE();
  const fs::path log = file("relative.ulg");
  const Recording r = read_recording(log, topic("sensor_combined"));
  expect_matches_reference(r, reference(log, "sensor_combined"));
  EXPECT_TRUE(r.time_s.empty());
  EXPECT_EQ(r.channel("gyro_x").values.size(), 300u);
  EXPECT_EQ(r.channel("accel_x").values.size(), 294u);  // every 50th message had no accelerometer data
  EXPECT_EQ(std::llround((r.channel("gyro_x").time_s[1] - r.channel("accel_x").time_s[0]) * 1e9), 13'000);
}

TEST_F(Ros2Ulog, UlogDataAppendedAfterACutMessageIsRead) {
  // The log stops inside a message; appended data follows at appended_offsets[0]. The
  // reference reader stops at that offset (it reads no appended data): the first 200 samples
  // match it, the 10 appended ones continue the 200 Hz series.
  REQUIRE_REFERENCE();
  const fs::path log = file("appended.ulg");
  const Recording r = read_recording(log, topic("sensor_combined"));
  ASSERT_EQ(r.sample_count(), 210u);
  const auto ref = reference(log, "sensor_combined").at("channels");
  ASSERT_EQ(ref.at("gyro_x").at("values").size(), 200u);
  for (std::size_t i = 0; i < 200; ++i) {
    ASSERT_EQ(r.channel("accel_z").values[i], ref.at("accel_z").at("values")[i].get<double>()) << i;
  }
  for (std::size_t i = 1; i < 210; ++i) ASSERT_EQ(std::llround((r.time_s[i] - r.time_s[i - 1]) * 1e9), 5'000'000) << i;
  // Without the flag the cut message is the corruption it looks like.
  std::string bytes = slurp(log);
  bytes[16 + 3 + 8] = 0;
  expect_input_error([&] { (void)read_ulog_buffer({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()}, "noflag.ulg", "sensor_combined"); },
                     {"noflag.ulg", "byte "});
  // An incompatible flag this reader does not know is refused, as the specification asks.
  bytes[16 + 3 + 8] = 2;
  expect_input_error([&] { (void)read_ulog_buffer({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()}, "newer.ulg", "sensor_combined"); },
                     {"newer.ulg", "unknown incompatible flag bits"});
}

TEST_F(Ros2Ulog, UlogChannelsOfOneInstanceBecomeOneTimeAxisOthersAreRefused) {
  const Recording gyro = read_recording(file("log.ulg"), topic("sensor_gyro"));
  const Recording one = select_channels(gyro, {"gyro1_x", "gyro1_y", "gyro1_z"});
  EXPECT_EQ(one.channel_list(), "gyro1_x, gyro1_y, gyro1_z");
  EXPECT_EQ(one.time_s, gyro.channel("gyro1_x").time_s);
  EXPECT_TRUE(one.channels[0].time_s.empty());
  expect_input_error([&] { (void)select_channels(gyro, {"gyro0_x", "gyro1_x"}); },
                     {"gyro0_x and gyro1_x were sampled at different times"});
}

TEST_F(Ros2Ulog, UlogUnknownOrMissingTopicListsTheLoggedTopics) {
  const fs::path log = file("log.ulg");
  expect_input_error([&] { (void)read_recording(log, topic("sensor_mag")); },
                     {"log.ulg", "no topic sensor_mag", "pass --topic with one of sensor_combined, vehicle_imu",
                      "sensor_gyro               IMU, multi_id 0,1  3000 messages", "vehicle_status            multi_id 0  75 messages"});
  expect_input_error([&] { (void)read_recording(log, topic("vehicle_status")); }, {"vehicle_status is not an IMU topic"});
  expect_input_error([&] { (void)read_recording(log, {}); }, {"no --topic given"});
}

TEST_F(Ros2Ulog, UlogTruncatedIsRefusedWithTheByteOffset) {
  const std::string bytes = slurp(file("log.ulg"));
  test::TempDir dir;
  // Cut inside the last message, inside the header, inside the definitions.
  for (const std::size_t cut : {bytes.size() - 5, std::size_t{10}, std::size_t{200}}) {
    SCOPED_TRACE(cut);
    const fs::path path = dir.write("cut.ulg", std::string_view(bytes).substr(0, cut));
    const std::string message = expect_input_error([&] { (void)read_recording(path, topic("sensor_combined")); },
                                                   {"cut.ulg", "byte "});
    if (cut > 16) {
      EXPECT_NE(message.find("cut short"), std::string::npos) << message;
    }
  }
  // Every prefix: read (a cut between messages is a shorter log) or refused, never a crash.
  for (std::size_t k = 0; k < 60; ++k) {
    const std::size_t cut = bytes.size() * k / 60;
    try {
      (void)read_ulog_buffer({reinterpret_cast<const unsigned char*>(bytes.data()), cut}, "prefix.ulg", "sensor_gyro");
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("prefix.ulg"), std::string::npos) << e.what();
    }
  }
}

TEST_F(Ros2Ulog, UlogCorruptedBytesAreRefusedOrReadNeverCrash) {
  const std::string bytes = slurp(file("log.ulg"));
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::string bad = bytes;
    for (int k = 0; k < 4; ++k) bad[16 + rng() % (bad.size() - 16)] = static_cast<char>(rng());
    try {
      (void)read_ulog_buffer({reinterpret_cast<const unsigned char*>(bad.data()), bad.size()}, "bad.ulg",
                             trial % 2 ? "vehicle_imu" : "sensor_combined");
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.ulg"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("fix:"), std::string::npos) << e.what();
    }
  }
}

TEST_F(Ros2Ulog, UlgExtensionOnAnotherFileIsRefused) {
  test::TempDir dir;
  const fs::path path = dir.write("flight.ulg", "t,gx\n0,1\n0.01,2\n");
  EXPECT_EQ(detect_container(path), RecordingFormat::ulog);
  expect_input_error([&] { (void)read_recording(path, topic("sensor_combined")); }, {"flight.ulg", "not a PX4 ULog file"});
  const auto r = run_cli({"dev", path.string(), "--topic", "sensor_combined", "--column", "gyro_x"}, dir.path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a PX4 ULog file"), std::string::npos) << r.err;
}

TEST_F(Ros2Ulog, PyulogSampleLogMatchesTheReferenceReader) {
  REQUIRE_REFERENCE();
  // A real flight log (PX4's pyulog test/sample_log_small.ulg, BSD; tests/data/ulog/README.md):
  // three IMUs, so vehicle_imu gives gyro0_x .. accel2_z.
  ASSERT_TRUE(fs::exists(kSampleLog));
  for (const char* t : {"sensor_combined", "vehicle_angular_velocity", "vehicle_imu", "sensor_accel"}) {
    SCOPED_TRACE(t);
    const Recording r = read_recording(kSampleLog, topic(t));
    expect_matches_reference(r, reference(kSampleLog, t));
  }
  EXPECT_EQ(read_recording(kSampleLog, topic("sensor_combined")).sample_count(), 1298u);
  EXPECT_EQ(read_recording(kSampleLog, topic("vehicle_imu")).channels.size(), 18u);
}

TEST_F(Ros2Ulog, CliReadsDb3AndUlogThroughTheOneLoader) {
  test::TempDir out;
  const fs::path bag = file("bag_le");
  const fs::path log = file("log.ulg");
  const auto dev = run_cli({"dev", bag.string(), "--topic", "/imu", "--column", "gyro_z", "--no-ci"}, out.path());
  EXPECT_EQ(dev.exit_code, 0) << dev.err;
  EXPECT_NE(dev.out.find("1500 samples"), std::string::npos) << dev.out;
  EXPECT_NE(dev.out.find("200 Hz"), std::string::npos) << dev.out;
  const auto file_dev = run_cli({"dev", (bag / "bag_le_0.db3").string(), "--topic", "/imu", "--column", "accel_z",
                                 "--no-ci"}, out.path());
  EXPECT_EQ(file_dev.exit_code, 0) << file_dev.err;
  const auto wrong = run_cli({"dev", bag.string(), "--topic", "/imu/data", "--column", "gyro_z"}, out.path());
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("/temperature"), std::string::npos) << wrong.err;
  // One sensor instance of several, with its own timestamps; the dropouts are said.
  const auto gyro = run_cli({"fit", log.string(), "--topic", "sensor_gyro", "--column", "gyro1_x",
                             "--format", "table"}, out.path());
  EXPECT_EQ(gyro.exit_code, 0) << gyro.err;
  EXPECT_NE((gyro.out + gyro.err).find("dropped data 2 times"), std::string::npos) << gyro.out << gyro.err;
  const auto analyze = run_cli({"analyze", log.string(), "--topic", "vehicle_imu", "-q", "-o",
                                (out.path() / "analyze").string()}, out.path());
  EXPECT_EQ(analyze.exit_code, 0) << analyze.err;
  EXPECT_TRUE(fs::exists(out.path() / "analyze" / "report.json"));
  const std::string report = slurp(out.path() / "analyze" / "report.json");
  EXPECT_NE(report.find("accel1_z"), std::string::npos);
  // The fleet and the redundant unit's fusion load through the same road.
  const auto fleet = run_cli({"fleet", bag.string(), bag.string(), "--topic", "/imu", "--column", "gyro_x", "-q", "-o",
                              (out.path() / "fleet").string()}, out.path());
  EXPECT_EQ(fleet.exit_code, 0) << fleet.err;
  EXPECT_NE(fleet.out.find("2 analysed, 0 failed"), std::string::npos) << fleet.out << fleet.err;
  const std::string l = log.string();
  const auto fuse = run_cli({"redundant", "--geometry", "tetra", "--fuse", l, l, l, l, "--topic", "sensor_combined",
                             "--column", "gyro_z", "--format", "table"}, out.path());
  EXPECT_EQ(fuse.exit_code, 0) << fuse.err;
}

}  // namespace
}  // namespace imunoise::io
