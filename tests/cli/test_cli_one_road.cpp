// What the one road from a file to a result mends, tried as a new user would: every command
// reads through the same loader with the same options, so what works in `dev` works in
// `analyze`, `fleet` and `redundant --fuse`.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace imunoise::test {
namespace {

// `n` rows of white-noise gyro rates at 200 Hz: "t,gx" (seconds), optionally with a gap of
// `gap_s` seconds after the middle row.
std::string timed_csv(std::size_t n, unsigned seed, double gap_s = 0.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 0.01);
  std::string text = "t,gx\n";
  char line[96];
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / 200.0 + (i >= n / 2 ? gap_s : 0.0);
    std::snprintf(line, sizeof line, "%.4f,%.17g\n", t, normal(rng));
    text += line;
  }
  return text;
}

// A EuRoC imu0/data.csv of `n` rows at 200 Hz.
std::string euroc_csv(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1e-3);
  std::string text = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                     "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  char line[256];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  1403636579758555392LL + 5000000LL * static_cast<long long>(i), normal(rng), normal(rng),
                  normal(rng), 0.1 + normal(rng), normal(rng), 9.81 + normal(rng));
    text += line;
  }
  return text;
}

TEST(CliOneRoad, AnalyzeStudiesEveryChannelOfAEurocFileWithoutColumns) {
  TempDir dir;
  const auto file = dir.write("data.csv", euroc_csv(4000, 1));
  const auto r = run_cli({"analyze", file, "-q", "-o", dir.file("report")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(dir.file("report") + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 6u);
  EXPECT_EQ(doc["channels"][0]["name"], "gyro_x");
  EXPECT_EQ(doc["channels"][0]["unit"], "rad/s");
  EXPECT_EQ(doc["channels"][5]["name"], "accel_z");
  EXPECT_EQ(doc["channels"][5]["unit"], "m/s^2");
  EXPECT_EQ(doc["channels"][0]["recording"]["format"], "EuRoC CSV");
}

TEST(CliOneRoad, AnalyzeSplitsAtAGapAndTheReportSaysSo) {
  TempDir dir;
  const auto file = dir.write("gap.csv", timed_csv(40000, 2, 5.0));
  const auto refused = run_cli({"analyze", file, "--units", "deg/s", "-q", "-o", dir.file("a")});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("gap"), std::string::npos) << refused.err;
  const auto r = run_cli({"analyze", file, "--units", "deg/s", "--gaps", "split", "--detrend", "linear",
                          "-q", "-o", dir.file("b")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(dir.file("b") + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 1u);  // t is the time column, not a channel
  const auto& steps = doc["channels"][0]["preprocessing"];
  ASSERT_TRUE(steps.is_array()) << doc["channels"][0].dump();
  std::string all;
  for (const auto& s : steps) all += s.get<std::string>() + "\n";
  EXPECT_NE(all.find("detrend"), std::string::npos) << all;
  EXPECT_NE(all.find("segments"), std::string::npos) << all;
}

TEST(CliOneRoad, TimestampNamedColumnIsTheTimeNotAGyro) {
  TempDir dir;
  const auto file = dir.write("imu.csv", timed_csv(8000, 3));
  const auto dev = run_cli({"dev", file, "--column", "gx", "--units", "deg/s", "--no-ci"});
  ASSERT_EQ(dev.exit_code, 0) << dev.err;
  EXPECT_NE(dev.out.find("200 Hz"), std::string::npos) << dev.out;
  EXPECT_NE(dev.err.find("column 't' is read as the timestamps"), std::string::npos) << dev.err;
  const auto analyze = run_cli({"analyze", file, "--units", "deg/s", "-q", "-o", dir.file("r")});
  ASSERT_EQ(analyze.exit_code, 0) << analyze.err;
  const auto doc = nlohmann::json::parse(slurp(dir.file("r") + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 1u);
  EXPECT_EQ(doc["channels"][0]["name"], "gx");
  EXPECT_NEAR(doc["channels"][0]["rate_hz"].get<double>(), 200.0, 1e-9);  // from timestamps to 4 decimals
}

TEST(CliOneRoad, DavarReachesDevAndFitJson) {
  TempDir dir;
  const auto file = dir.write("imu.csv", timed_csv(24000, 4));
  const auto dev = run_cli({"dev", file, "--column", "gx", "--units", "deg/s", "--davar", "--format", "json"});
  ASSERT_EQ(dev.exit_code, 0) << dev.err;
  const auto d = nlohmann::json::parse(dev.out);
  ASSERT_TRUE(d.contains("davar")) << dev.out.substr(0, 400);
  EXPECT_FALSE(d["davar"]["tau_s"].empty());
  EXPECT_FALSE(d["davar"]["window_start_s"].empty());
  EXPECT_EQ(d["davar"]["avar_si"].size(), d["davar"]["window_start_s"].size());
  const auto fit = run_cli({"fit", file, "--column", "gx", "--units", "deg/s", "--davar"});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto f = nlohmann::json::parse(fit.out);
  ASSERT_TRUE(f.contains("davar"));
  EXPECT_EQ(f["davar"]["tau_s"], d["davar"]["tau_s"]);
}

TEST(CliOneRoad, GeometryNeedsOneChannelPerSensor) {
  TempDir dir;
  const auto file = dir.write("imu.csv", timed_csv(8000, 5));
  const auto r = run_cli({"analyze", file, "--units", "deg/s", "--geometry", "tetra", "-q", "-o", dir.file("r")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("4 sensors but 1 channel"), std::string::npos) << r.err;
}

TEST(CliOneRoad, FleetAcceptsQuietAndFusedCsvReadsBack) {
  TempDir dir;
  std::vector<std::string> files;
  for (unsigned s = 0; s < 4; ++s) files.push_back(dir.write("g" + std::to_string(s) + ".csv", timed_csv(8000, 10 + s)));
  const auto fleet = run_cli({"fleet", files[0], files[1], "--units", "deg/s", "-q", "-o", dir.file("fleet")});
  EXPECT_EQ(fleet.exit_code, 0) << fleet.err;
  const auto fuse = run_cli({"redundant", "--geometry", "tetra", "--fuse", files[0], files[1], files[2], files[3],
                             "--units", "deg/s", "-o", dir.file("fused.csv")});
  ASSERT_EQ(fuse.exit_code, 0) << fuse.err;
  // The fused CSV (t_s,x,y,z,p1) is read by dev without --time-column: t_s is its time.
  const auto dev = run_cli({"dev", dir.file("fused.csv"), "--column", "x", "--units", "deg/s", "--no-ci"});
  ASSERT_EQ(dev.exit_code, 0) << dev.err;
  EXPECT_NE(dev.out.find("200 Hz"), std::string::npos) << dev.out;
}

}  // namespace
}  // namespace imunoise::test
