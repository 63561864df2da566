// Container readers on files written by the real libraries: ROS 1 bags by python3-rosbag,
// MCAP by the reference TypeScript writer (@mcap/core + @foxglove/cdr, pinned in
// tests/io/mcap_writer/package-lock.json), HDF5 by python3-h5py. Each writer also saves the
// values it wrote (float64, exact), and the reader must return them bit for bit. Then the
// refusals: missing or wrong-type topic (listing what the file holds), truncated and
// corrupted files (an InputError naming the file, never a crash).
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

#include <array>
#include <cstdio>
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
const fs::path kMcapWriter = kTests / "io" / "mcap_writer";

std::string slurp_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<double> read_f64(const fs::path& path) {
  const std::string bytes = slurp_bytes(path);
  std::vector<double> out(bytes.size() / 8);
  std::memcpy(out.data(), bytes.data(), out.size() * 8);
  return out;
}

RecordingOptions topic(std::string name) {
  RecordingOptions o;
  o.topic = std::move(name);
  return o;
}
RecordingOptions dataset(std::string name, std::string time = "") {
  RecordingOptions o;
  o.dataset = std::move(name);
  o.time_dataset = std::move(time);
  return o;
}

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs the imunoise executable with arguments (no shell quoting needed for these paths).
CliResult run_cli(const std::vector<std::string>& args, const test::TempDir& dir) {
  std::string command = IMUNOISE_CLI_PATH;
  for (const auto& a : args) command += " '" + a + "'";
  const auto out = dir.path() / "out.txt";
  const auto err = dir.path() / "err.txt";
  command += " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp_bytes(out);
  r.err = slurp_bytes(err);
  return r;
}

bool run(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()) == 0; }

// One directory of generated files for the whole suite (writing them costs ~1 s of Python).
// Files are written on first use and shared by the tests of one process (ctest runs each test
// in its own process: writing every file up front would cost each of them ~10 s).
class Containers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    have_bag_ = run("/usr/bin/python3 -c 'import rosbag, sensor_msgs.msg'");
    have_h5_ = run("/usr/bin/python3 -c 'import h5py'");
    have_mcap_ = fs::exists(kMcapWriter / "node_modules" / "@mcap" / "core") && run("node --version");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  // imu_<none|bz2|lz4>.bag, imu_<none|zstd|lz4>_<summary|nosummary>.mcap, imu.h5.
  static fs::path file(const std::string& name) {
    const fs::path path = dir_->path() / name;
    if (fs::exists(path)) return path;
    std::string command;
    if (name == "imu.h5") {
      command = "/usr/bin/python3 " + (kWriters / "write_h5.py").string() + " " + path.string() + " 700";
    } else if (name.ends_with(".bag")) {
      const std::string c = name.substr(4, name.size() - 8);
      command = "/usr/bin/python3 " + (kWriters / "write_bag.py").string() + " " + path.string() + " " + c + " 1500";
    } else {
      const auto under = name.find('_', 4);
      const std::string c = name.substr(4, under - 4);
      const std::string summary = name.substr(under + 1, name.size() - 5 - under - 1);
      command = "node " + (kMcapWriter / "write_mcap.js").string() + " " + path.string() + " " + c + " 1500 200 " + summary;
    }
    if (!run(command)) ADD_FAILURE() << "the writer failed: " << command;
    return path;
  }

  // The reader's recording equals the writer's values bit for bit; time from integer ns.
  static void expect_bit_exact(const Recording& r, const fs::path& expected_path, std::size_t n) {
    const std::vector<double> expected = read_f64(expected_path);
    ASSERT_EQ(expected.size(), n * 7);
    ASSERT_EQ(r.sample_count(), n);
    ASSERT_EQ(r.time_s.size(), n);
    const char* names[] = {"gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"};
    for (std::size_t k = 0; k < 6; ++k) {
      const Channel& c = r.channel(names[k]);
      ASSERT_TRUE(c.unit.has_value());
      EXPECT_EQ(c.unit->name, k < 3 ? "rad/s" : "m/s^2");
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(c.values[i]), std::bit_cast<std::uint64_t>(expected[i * 7 + 1 + k]))
            << names[k] << " sample " << i;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      // (stamp - first) is an exact integer number of ns: the reader keeps 1 ns resolution.
      ASSERT_EQ(std::llround(r.time_s[i] * 1e9), std::llround(expected[i * 7])) << "time of sample " << i;
    }
  }

  static inline test::TempDir* dir_ = nullptr;
  static inline bool have_bag_ = false;
  static inline bool have_h5_ = false;
  static inline bool have_mcap_ = false;
};

#define REQUIRE(flag, what) \
  if (!(flag)) GTEST_SKIP() << what

TEST_F(Containers, BagFromRosbagReadsBackBitExactForEveryCompression) {
  REQUIRE(have_bag_, "python3-rosbag / python3-sensor-msgs not installed (scripts/setup.sh)");
  for (const char* c : {"none", "bz2", "lz4"}) {
    SCOPED_TRACE(c);
    const fs::path path = file(std::string("imu_") + c + ".bag");
    EXPECT_EQ(detect_container(path), RecordingFormat::ros1_bag);
    const Recording r = read_recording(path, topic("/imu/data"));
    EXPECT_EQ(r.format, RecordingFormat::ros1_bag);
    EXPECT_EQ(r.message_type, "sensor_msgs/Imu");
    EXPECT_EQ(r.time_origin, "1700000000123456789 ns");
    expect_bit_exact(r, path.string() + ".expected", 1500);
  }
}

TEST_F(Containers, McapFromReferenceWriterReadsBackBitExact) {
  REQUIRE(have_mcap_, "node_modules missing: run 'npm ci' in tests/io/mcap_writer (.ci/run does)");
  for (const char* c : {"none", "zstd", "lz4"}) {
    for (const char* s : {"summary", "nosummary"}) {
      SCOPED_TRACE(std::string(c) + " " + s);
      const fs::path path = file(std::string("imu_") + c + "_" + s + ".mcap");
      EXPECT_EQ(detect_container(path), RecordingFormat::mcap);
      const Recording r = read_recording(path, topic("/imu"));
      EXPECT_EQ(r.message_type, "sensor_msgs/msg/Imu");
      expect_bit_exact(r, path.string() + ".expected", 1500);
    }
  }
}

TEST_F(Containers, Hdf5FromH5pyReadsBackBitExact) {
  REQUIRE(have_h5_, "python3-h5py not installed (scripts/setup.sh)");
  const fs::path path = file("imu.h5");
  const std::vector<double> e = read_f64(path.string() + ".expected");
  const std::size_t n = 700;
  ASSERT_EQ(e.size(), n * 5);
  const Recording two_d = read_recording(path, dataset("/imu/gyro", "/imu/time"));
  ASSERT_EQ(two_d.channels.size(), 3u);
  EXPECT_EQ(two_d.channels[1].name, "gyro[1]");
  ASSERT_TRUE(two_d.channels[0].unit.has_value());
  EXPECT_EQ(two_d.channels[0].unit->name, "rad/s");
  const Recording one_d = read_recording(path, dataset("imu/gyro_x"));  // float32, no leading '/'
  const Recording ints = read_recording(path, dataset("/counts"));      // int16
  EXPECT_TRUE(one_d.time_s.empty());
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(two_d.channels[k].values[i]), std::bit_cast<std::uint64_t>(e[i * 5 + k]));
    }
    ASSERT_EQ(std::bit_cast<std::uint64_t>(one_d.channels[0].values[i]), std::bit_cast<std::uint64_t>(e[i * 5 + 3]));
    ASSERT_EQ(ints.channels[0].values[i], e[i * 5 + 4]);
    ASSERT_EQ(std::llround(two_d.time_s[i] * 1e9), static_cast<long long>(i) * 10'000'000);  // epoch ns detected
  }
}

TEST_F(Containers, MissingTopicListsTopicsWithTypesAndCounts) {
  REQUIRE(have_bag_ && have_mcap_, "writers not available");
  expect_input_error([&] { (void)read_recording(file("imu_lz4.bag"), topic("/imu")); },
                                             {"imu_lz4.bag", "no topic /imu", "/imu/data", "sensor_msgs/Imu",
                                              "1500 messages", "/status", "std_msgs/String", "3 messages"});
  expect_input_error([&] { (void)read_recording(file("imu_none.bag"), {}); },
                                              {"no --topic given", "/imu/data"});
  for (const char* s : {"summary", "nosummary"}) {
    // With the summary the counts come from the statistics record; without, from the scan.
    expect_input_error([&] { (void)read_recording(file(std::string("imu_zstd_") + s + ".mcap"), topic("/imu/data")); },
                       {"no topic /imu/data", "/imu     sensor_msgs/msg/Imu  1500 messages",
                        "std_msgs/msg/String  3 messages"});
  }
}

TEST_F(Containers, TopicOfAnotherTypeSaysWhichType) {
  REQUIRE(have_bag_ && have_mcap_, "writers not available");
  expect_input_error([&] { (void)read_recording(file("imu_bz2.bag"), topic("/status")); },
                     {"topic /status has type std_msgs/String, not sensor_msgs/Imu"});
  expect_input_error([&] { (void)read_recording(file("imu_lz4_summary.mcap"), topic("/status")); },
                     {"topic /status has type std_msgs/msg/String"});
}

TEST_F(Containers, MissingDatasetListsDatasets) {
  REQUIRE(have_h5_, "python3-h5py not installed");
  expect_input_error([&] { (void)read_recording(file("imu.h5"), dataset("/imu/accel")); },
                     {"imu.h5", "no dataset /imu/accel", "/imu/gyro    float [700 x 3]  700 rows", "/counts      integer [700]  700 rows"});
  expect_input_error([&] { (void)read_recording(file("imu.h5"), dataset("/imu")); }, {"not a dataset"});
  expect_input_error([&] { (void)read_recording(file("imu.h5"), dataset("/imu/gyro", "/counts/x")); },
                     {"no dataset /counts/x"});
  expect_input_error([&] { (void)read_recording(file("imu.h5"), topic("/imu")); }, {"--topic applies to"});
}

// Every prefix of a file is read or refused with an InputError naming it; never a crash.
// (Offsets: a sample of cut points over the whole file, plus the last 64 bytes one by one.)
void expect_truncations_refused(const fs::path& path, const RecordingOptions& options, const test::TempDir& dir) {
  const std::string bytes = slurp_bytes(path);
  std::vector<std::size_t> cuts;
  for (std::size_t k = 0; k < 40; ++k) cuts.push_back(bytes.size() * k / 40);
  for (std::size_t k = 1; k <= 64 && k < bytes.size(); ++k) cuts.push_back(bytes.size() - k);
  for (const std::size_t cut : cuts) {
    const fs::path cut_path = dir.write("cut" + path.extension().string(), std::string_view(bytes).substr(0, cut));
    try {
      (void)read_recording(cut_path, options);
      // A cut that removes only the summary or index is readable by the linear scan.
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cut"), std::string::npos) << e.what();
    }
  }
}

TEST_F(Containers, TruncatedFilesAreRefusedOrReadNeverCrash) {
  REQUIRE(have_bag_ && have_mcap_ && have_h5_, "writers not available");
  test::TempDir dir;
  expect_truncations_refused(file("imu_lz4.bag"), topic("/imu/data"), dir);
  expect_truncations_refused(file("imu_none.bag"), topic("/imu/data"), dir);
  expect_truncations_refused(file("imu_zstd_summary.mcap"), topic("/imu"), dir);
  expect_truncations_refused(file("imu_none_nosummary.mcap"), topic("/imu"), dir);
  expect_truncations_refused(file("imu.h5"), dataset("/imu/gyro"), dir);
  // A bag cut in the middle of its chunks is refused, naming the byte.
  const std::string bag = slurp_bytes(file("imu_none.bag"));
  const fs::path half = dir.write("half.bag", std::string_view(bag).substr(0, bag.size() / 2));
  expect_input_error([&] { (void)read_recording(half, topic("/imu/data")); }, {"half.bag", "byte"});
}

TEST_F(Containers, CorruptedBytesAreRefusedOrReadNeverCrash) {
  REQUIRE(have_bag_ && have_mcap_, "writers not available");
  std::mt19937_64 rng(16);
  for (const char* name : {"imu_bz2.bag", "imu_lz4.bag", "imu_none.bag", "imu_zstd_summary.mcap", "imu_lz4_nosummary.mcap"}) {
    const std::string bytes = slurp_bytes(file(name));
    const RecordingOptions options = topic(std::string(name).ends_with(".bag") ? "/imu/data" : "/imu");
    for (int trial = 0; trial < 60; ++trial) {
      std::string bad = bytes;
      for (int k = 0; k < 4; ++k) bad[rng() % bad.size()] = static_cast<char>(rng());
      try {
        if (options.topic == "/imu") (void)read_mcap_buffer({reinterpret_cast<const unsigned char*>(bad.data()), bad.size()}, name, options.topic);
        else (void)read_ros1_bag_buffer({reinterpret_cast<const unsigned char*>(bad.data()), bad.size()}, name, options.topic);
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      }
    }
  }
}

TEST(Euroc, HeaderRecognisedChannelsUnitsAndNanosecondTime) {
  test::TempDir dir;
  const fs::path path = dir.write("data.csv",
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n"
      "1403636579758555392,-0.099134701513277898,0.14730578886832138,0.02722713633111154,8.1476917083333333,-0.37592158333333331,-2.4026292499999999\n"
      "1403636579763555584,-0.099134701513277898,0.14032447186034408,0.029321531433504733,8.033280791666666,-0.40861041666666664,-2.4026292499999999\n"
      "1403636579768555520,-0.098436569812480182,0.12775810124598494,0.037699111843077518,7.8861810416666662,-0.42495483333333334,-2.4353180833333332\n");
  ASSERT_EQ(detect_container(path), RecordingFormat::euroc);
  const Recording r = read_recording(path, {});
  ASSERT_EQ(r.channel_list(), "gyro_x, gyro_y, gyro_z, accel_x, accel_y, accel_z");
  EXPECT_EQ(r.channel("gyro_y").unit->name, "rad/s");
  EXPECT_EQ(r.channel("accel_z").unit->name, "m/s^2");
  EXPECT_EQ(r.channel("gyro_x").values[2], -0.098436569812480182);
  EXPECT_EQ(r.channel("5").values[1], -2.4026292499999999);
  ASSERT_EQ(r.time_s.size(), 3u);
  EXPECT_EQ(r.time_s[1], 5000192e-9);
  EXPECT_EQ(r.time_s[2], 10000128e-9);
  expect_input_error([&] { (void)r.channel("gyro_w"); }, {"data.csv", "no channel 'gyro_w'", "gyro_x, gyro_y"});
  // A header that is not EuRoC's is plain text (no container).
  const fs::path plain = dir.write("plain.csv", "#timestamp,gx\n1,2\n");
  EXPECT_FALSE(detect_container(plain).has_value());
}

TEST_F(Containers, CliReadsBagMcapAndHdf5AndExitsOneOnAWrongTopic) {
  REQUIRE(have_bag_ && have_mcap_ && have_h5_, "writers not available");
  const auto bag = run_cli({"dev", file("imu_lz4.bag").string(), "--topic", "/imu/data", "--column", "gyro_z"}, *dir_);
  EXPECT_EQ(bag.exit_code, 0) << bag.err;
  EXPECT_NE(bag.out.find("1500 samples"), std::string::npos) << bag.out;
  EXPECT_NE(bag.out.find("200 Hz"), std::string::npos) << bag.out;
  const auto mcap = run_cli({"dev", file("imu_zstd_summary.mcap").string(), "--topic", "/imu", "--column", "accel_x"}, *dir_);
  EXPECT_EQ(mcap.exit_code, 0) << mcap.err;
  const auto h5 = run_cli({"dev", file("imu.h5").string(), "--dataset", "/imu/gyro", "--time-dataset",
                                 "/imu/time", "--column", "1"}, *dir_);
  EXPECT_EQ(h5.exit_code, 0) << h5.err;
  EXPECT_NE(h5.out.find("100 Hz"), std::string::npos) << h5.out;
  const auto wrong = run_cli({"dev", file("imu_lz4.bag").string(), "--topic", "/imu"}, *dir_);
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("/imu/data"), std::string::npos) << wrong.err;
  const auto no_column = run_cli({"dev", file("imu_lz4.bag").string(), "--topic", "/imu/data"}, *dir_);
  EXPECT_EQ(no_column.exit_code, 1);
  EXPECT_NE(no_column.err.find("choose one with --column"), std::string::npos) << no_column.err;
  const auto units = run_cli({"dev", file("imu_lz4.bag").string(), "--topic", "/imu/data", "--column",
                                    "gyro_x", "--units", "deg/s"}, *dir_);
  EXPECT_EQ(units.exit_code, 1);
  EXPECT_NE(units.err.find("drop --units"), std::string::npos) << units.err;
}

// Every command that reads a file binds the loader's options with one binder and loads through
// the one loader: each of them reads each format. Gyro channel of each file, its options.
struct FormatCase {
  std::string label;
  std::string file;
  std::vector<std::string> options;  ///< how to read it (topic, dataset, rate, units)
  std::string column;
};

std::vector<FormatCase> format_cases(const test::TempDir& dir, const fs::path& bag, const fs::path& mcap,
                                     const fs::path& h5) {
  std::mt19937_64 rng(23);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::string csv = "t,gx,gy\n";
  std::string euroc = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  std::vector<double> f64;
  char line[256];
  for (int i = 0; i < 1500; ++i) {
    const double gx = noise(rng), gy = noise(rng);
    std::snprintf(line, sizeof line, "%.3f,%.17g,%.17g\n", i / 200.0, gx, gy);
    csv += line;
    std::snprintf(line, sizeof line, "%lld,%.17g,%.17g,%.17g,0.1,0.2,9.81\n",
                  1403636579758555392LL + 5000000LL * i, gx, gy, noise(rng));
    euroc += line;
    f64.push_back(gx);
  }
  const fs::path raw = dir.path() / "gyro.f64";
  std::ofstream(raw, std::ios::binary).write(reinterpret_cast<const char*>(f64.data()),
                                             static_cast<std::streamsize>(f64.size() * sizeof(double)));
  fs::create_directories(dir.path() / "mav0" / "imu0");
  return {
      {"text", dir.write("gyro.csv", csv).string(), {"--units", "rad/s"}, "gx"},
      {"binary", raw.string(), {"--rate", "200", "--units", "rad/s"}, "0"},
      {"bag", bag.string(), {"--topic", "/imu/data"}, "gyro_x"},
      {"mcap", mcap.string(), {"--topic", "/imu"}, "gyro_x"},
      {"hdf5", h5.string(), {"--dataset", "/imu/gyro", "--time-dataset", "/imu/time", "--units", "rad/s"}, "0"},
      {"euroc", dir.write("mav0/imu0/data.csv", euroc).string(), {}, "gyro_x"},
  };
}

std::vector<std::string> joined(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST_F(Containers, EveryCommandReadsEveryFormatThroughTheOneLoader) {
  REQUIRE(have_bag_ && have_mcap_ && have_h5_, "writers not available");
  test::TempDir out;
  const auto cases = format_cases(out, file("imu_lz4.bag"), file("imu_zstd_summary.mcap"), file("imu.h5"));
  for (const auto& c : cases) {
    SCOPED_TRACE(c.label);
    const auto dev = run_cli(joined({"dev", c.file, "--column", c.column, "--no-ci"}, c.options), out);
    EXPECT_EQ(dev.exit_code, 0) << dev.err;
    const auto fit = run_cli(joined({"fit", c.file, "--column", c.column, "--format", "table"}, c.options), out);
    EXPECT_EQ(fit.exit_code, 0) << fit.err;
    EXPECT_NE(fit.out.find("rad/s"), std::string::npos) << fit.out;
    const auto analyze = run_cli(joined({"analyze", c.file, "--columns", c.column, "-q", "-o",
                                         (out.path() / ("analyze-" + c.label)).string()}, c.options), out);
    EXPECT_EQ(analyze.exit_code, 0) << analyze.err;
    EXPECT_TRUE(fs::exists(out.path() / ("analyze-" + c.label) / "report.json"));
    const auto fleet = run_cli(joined({"fleet", c.file, c.file, "--column", c.column, "-q", "-o",
                                       (out.path() / ("fleet-" + c.label)).string()}, c.options), out);
    EXPECT_EQ(fleet.exit_code, 0) << fleet.err;
    EXPECT_NE(fleet.out.find("2 analysed, 0 failed"), std::string::npos) << fleet.out << fleet.err;
    const auto fuse = run_cli(joined({"redundant", "--geometry", "tetra", "--fuse", c.file, c.file, c.file,
                                      c.file, "--column", c.column, "--format", "table"}, c.options), out);
    EXPECT_EQ(fuse.exit_code, 0) << fuse.err;
  }
}

}  // namespace
}  // namespace imunoise::io

namespace imunoise::io {
namespace {

TEST(MixedRates, EurocWithARateChangeIsRefusedNamingTheFileAndBothRates) {
  test::TempDir dir;
  std::string text = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                     "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  long long t = 1403636579758555392LL;
  for (int i = 0; i < 4000; ++i) {
    t += i < 2000 ? 5'000'000 : 10'000'000;  // 200 Hz, then 100 Hz
    text += std::to_string(t) + ",0.001,0.002,0.003,0.1,0.2,9.8\n";
  }
  const auto path = dir.write("mixed.csv", text);
  const auto r = run_cli({"dev", path.string(), "--column", "gyro_x"}, dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("mixed.csv: mixed sample rates"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("200 Hz over the first tenth"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("100 Hz over the last"), std::string::npos) << r.err;
  // Splitting at gaps cannot help either: a split record would pool two sample intervals.
  const auto split = run_cli({"dev", path.string(), "--column", "gyro_x", "--gaps", "split"}, dir);
  EXPECT_EQ(split.exit_code, 1);
}

}  // namespace
}  // namespace imunoise::io

namespace imunoise::io {
namespace {

TEST(TextRecording, ColumnsBecomeNamedChannelsWithTheTimeColumn) {
  test::TempDir dir;
  const auto path = dir.write("imu.csv", "t,gx,gy\n0.00,1.5,-2\n0.01,2.5,-3\n0.02,3.5,-4\n");
  const Recording all = read_text_recording(path, {}, "t");
  EXPECT_EQ(all.format, RecordingFormat::text);
  ASSERT_EQ(all.channel_list(), "gx, gy");
  EXPECT_EQ(all.channel("gy").values, (std::vector<double>{-2, -3, -4}));
  ASSERT_EQ(all.time_s.size(), 3u);
  EXPECT_DOUBLE_EQ(all.time_s[2], 0.02);
  EXPECT_FALSE(all.channel("gx").unit.has_value());
  const Recording one = read_text_recording(path, {"gy"});
  EXPECT_EQ(one.channel_list(), "gy");
  EXPECT_TRUE(one.time_s.empty());
  expect_input_error([&] { (void)read_text_recording(path, {"gz"}); }, {"imu.csv", "gz"});
}

}  // namespace
}  // namespace imunoise::io
