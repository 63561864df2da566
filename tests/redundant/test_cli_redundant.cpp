// `imunoise redundant` as a user runs it: simulate four gyros, fit them, analyse the unit from
// the fits, fuse the recordings and run the fused axes through `dev`; bad input exits 1 with a
// message naming the file.
#include <cmath>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"

namespace {

using imunoise::test::run_cli;
using imunoise::test::TempDir;

std::string simulate(const TempDir& dir, const std::string& name, int seed, const std::string& rate = "100",
                     const std::string& units = "deg/s") {
  const std::string file = dir.file(name);
  const auto r = run_cli({"simulate", "--rate", rate, "--duration", "1200", "--N", "8.9e-4", "--B", "5.9e-4",
                          "--units", units, "--seed", std::to_string(seed), "-o", file});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return file;
}

TEST(CliRedundant, GeometryOnlyFollowsTheContract) {
  const auto r = run_cli({"redundant", "--geometry", "tetra"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["geometry"], "tetra");
  EXPECT_NEAR(j["gdop"].get<double>(), 1.5, 1e-12);
  EXPECT_NEAR(j["axis_gain"][0].get<double>(), 0.8660254, 1e-7);
  EXPECT_NEAR(std::abs(j["parity"][0][1].get<double>()), 0.5, 1e-12);
  EXPECT_EQ(j["H"].size(), 4u);
  EXPECT_EQ(j["gdop_without"].size(), 4u);
  EXPECT_EQ(j["min_detectable_fault"].size(), 4u);
  EXPECT_TRUE(j["min_detectable_fault"][0].is_null());  // needs the sensors' models
  EXPECT_NEAR(j["false_alarm_per_hour"].get<double>(), 0.01, 1e-15);
  const auto t = run_cli({"redundant", "--geometry", "3+1", "--format", "table"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("GDOP 1.5811"), std::string::npos) << t.out;
}

TEST(CliRedundant, FromFitsFuseAndDetect) {
  TempDir dir;
  std::vector<std::string> recs, fits;
  for (int i = 0; i < 4; ++i) {
    recs.push_back(simulate(dir, std::string("g").append(std::to_string(i + 1)).append(".txt"), 10 + i));
    const auto f = run_cli({"fit", recs.back(), "--units", "deg/s", "-o", dir.file("fit" + std::to_string(i + 1) + ".json")});
    ASSERT_EQ(f.exit_code, 0) << f.err;
    fits.push_back(dir.file("fit" + std::to_string(i + 1) + ".json"));
  }
  std::vector<std::string> args{"redundant", "--geometry", "tetra", "--from"};
  args.insert(args.end(), fits.begin(), fits.end());
  const auto a = run_cli(args);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto j = nlohmann::json::parse(a.out);
  ASSERT_EQ(j["axes"].size(), 3u);
  // Fused N = sqrt(sum G^2 N_i^2) from the four fits; near 0.866 * 8.9e-4 deg/sqrt(s).
  EXPECT_NEAR(j["axes"][0]["N"]["value"].get<double>(), 0.866 * 8.9e-4, 0.03 * 0.866 * 8.9e-4);
  EXPECT_EQ(j["axes"][0]["N"]["unit"], "deg/sqrt(s)");
  EXPECT_TRUE(j["min_detectable_fault"][0].is_number());

  std::vector<std::string> fuse{"redundant", "--geometry", "tetra", "--fuse"};
  fuse.insert(fuse.end(), recs.begin(), recs.end());
  fuse.push_back("--from");
  fuse.insert(fuse.end(), fits.begin(), fits.end());
  for (const char* s : {"--units", "deg/s", "--detect", "-o"}) fuse.emplace_back(s);
  fuse.push_back(dir.file("fused.csv"));
  const auto f = run_cli(fuse);
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const auto jf = nlohmann::json::parse(f.out);
  ASSERT_TRUE(jf.contains("faults"));
  EXPECT_TRUE(jf["faults"].empty());
  EXPECT_EQ(jf["tests"].get<int>(), 1200 - 60);
  const std::string csv = imunoise::test::slurp(dir.file("fused.csv"));
  EXPECT_NE(csv.find("\nt_s,x,y,z,p1\n"), std::string::npos);
  // The fused axes are an ordinary record for dev.
  const auto d = run_cli({"dev", dir.file("fused.csv"), "--column", "x", "--time-column", "t_s", "--units", "deg/s"});
  EXPECT_EQ(d.exit_code, 0) << d.err;
  // Never overwritten without --force.
  const auto again = run_cli(fuse);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("fused.csv: file exists"), std::string::npos) << again.err;
}

// Six white-noise gyros (N = 1e-3 deg/sqrt(s) at 100 Hz, 200 s) as CSV files with a time column;
// sensor 4 steps by 0.05 deg/s (about 5 minimum detectable faults) at t = 120 s.
std::string gyro_csv(std::uint64_t seed, double step_deg_s, std::size_t samples = 20000) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1e-3 * std::sqrt(100.0));
  std::ostringstream out;
  out.precision(10);
  out << "t,gyro\n";
  for (std::size_t t = 0; t < samples; ++t) {
    out << static_cast<double>(t) / 100.0 << "," << normal(rng) + (t >= 12000 ? step_deg_s : 0.0) << "\n";
  }
  return out.str();
}

TEST(CliRedundant, DetectsAndIsolatesAStepInRecordings) {
  TempDir dir;
  std::vector<std::string> clean, faulty, fits;
  for (int i = 0; i < 6; ++i) {
    const std::string name = std::string("g").append(std::to_string(i + 1));
    // Sensor 6 is 10 samples longer: the shortest length is used, with a note.
    clean.push_back(dir.write(name + ".csv", gyro_csv(100 + static_cast<std::uint64_t>(i), 0.0, i == 5 ? 20010 : 20000)));
    faulty.push_back(i == 3 ? dir.write(name + "_step.csv", gyro_csv(103, 0.05)) : clean.back());
    fits.push_back(dir.file(name + ".json"));
    const auto f = run_cli({"fit", clean.back(), "--column", "gyro", "--time-column", "t", "--units", "deg/s", "-o", fits.back()});
    ASSERT_EQ(f.exit_code, 0) << f.err;
  }
  std::vector<std::string> args{"redundant", "--geometry", "cone:6:54.7356", "--column", "gyro", "--time-column", "t",
                                "--units", "deg/s", "--detect", "--fuse"};
  args.insert(args.end(), faulty.begin(), faulty.end());
  args.emplace_back("--from");
  args.insert(args.end(), fits.begin(), fits.end());
  const auto r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("g6.csv has 20010 samples"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["faults"].size(), 1u) << j["faults"].dump();
  EXPECT_EQ(j["faults"][0]["sensor"], 4);
  EXPECT_TRUE(j["faults"][0]["isolated"].get<bool>());
  EXPECT_NEAR(j["faults"][0]["t_s"].get<double>(), 120.0, 0.1);
  EXPECT_GT(j["faults"][0]["statistic"].get<double>(), j["faults"][0]["threshold"].get<double>());
  EXPECT_EQ(j["excluded_sensors"], nlohmann::json::array({4}));
}

TEST(CliRedundant, BadInputExitsOneNamingTheProblem) {
  TempDir dir;
  const auto a = simulate(dir, "a.txt", 1);
  const auto b = simulate(dir, "b.txt", 2);
  const auto c = simulate(dir, "c.txt", 3);
  const auto fast = simulate(dir, "fast.txt", 4, "200");
  const auto rad = simulate(dir, "rad.txt", 5, "100", "rad/s");
  auto expect_error = [](const std::vector<std::string>& args, const std::string& needle) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  };
  expect_error({"redundant", "--geometry", "tetra", "--fuse", a, b, c, "--units", "deg/s"}, "3 recordings for the 4 sensors");
  expect_error({"redundant", "--geometry", "tetra", "--fuse", a, b, c, fast, "--units", "deg/s"}, "fast.txt is sampled at 200 Hz");
  expect_error({"redundant", "--geometry", "tetra", "--fuse", a, b, c, rad, "--units", "deg/s"}, "rad.txt is in rad/s");
  expect_error({"redundant", "--geometry", "cone:2:50"}, "at least 3");
  expect_error({"redundant", "--geometry", dir.write("flat.csv", "1,0,0\n0,1,0\n1,1,0\n")}, "flat.csv: the 3 sensing axes do not span 3-D");
  expect_error({"redundant", "--geometry", dir.write("g4.csv", "1,0,0,0\n0,1,0,0\n0,0,1,0\n")}, "g4.csv:1: 4 fields");
  expect_error({"redundant", "--geometry", "tetra", "--fuse", a, b, c, a}, "--units");
  expect_error({"redundant", "--geometry", "tetra", "--from", dir.write("x.json", "{}"), a, b, c}, "x.json: not a fit document");
  expect_error({"redundant", "--geometry", "3+1", "--detect"}, "--fuse");
  expect_error({"redundant", "--geometry", "tetra", "--fuse", a, b, c, a, "--units", "deg/s", "--scale", "0"}, "--scale");
  expect_error({"redundant", "--geometry", "tetra", "--false-alarm-rate", "-1"}, "false_alarm_per_hour");
}

}  // namespace
