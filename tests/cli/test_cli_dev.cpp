// imunoise dev as a user runs it: results, formats, and every kind of bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>

#include "cli/cli_runner.hpp"
#include "core/nbs14.hpp"

namespace imunoise {
namespace {

using test::column_text;
using test::run_cli;
using test::TempDir;

void expect_input_error(const test::CliResult& r, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  for (const auto& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << "missing '" << f << "' in: " << r.err;
}

// NBS14 1000-point set through the whole CLI (text reader, integration, JSON writer), against
// the published values (7 digits -> 6e-7 relative).
TEST(CliDev, Nbs14ThroughJson) {
  TempDir dir;
  const auto file = dir.write("nbs14.txt", "# NBS14 1000-point set\n" + column_text(test::nbs14_1000_point_frequency()));
  const auto r = run_cli({"dev", file, "--rate", "1", "--input", "freq", "--estimator", "oadev,mdev",
                          "--af", "1,10,100", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 2u);
  const double oadev[] = {2.922319e-1, 9.159953e-2, 3.241343e-2};
  const double mdev[] = {2.922319e-1, 6.172376e-2, 2.170921e-2};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(j[0]["points"][i]["dev"].get<double>() / oadev[i], 1.0, 6e-7);
    EXPECT_NEAR(j[1]["points"][i]["dev"].get<double>() / mdev[i], 1.0, 6e-7);
  }
  EXPECT_EQ(j[0]["estimator"], "oadev");
  EXPECT_EQ(j[0]["n_samples"], 1000);
  EXPECT_EQ(j[0]["points"][2]["n"], 1001 - 200);
  EXPECT_EQ(j[0]["points"][1]["tau_s"], 10.0);
}

TEST(CliDev, TableAndCsvStateUnits) {
  TempDir dir;
  const auto file = dir.write("g.csv", "time,gyro\n" + [] {
    std::string s;
    for (int i = 0; i < 400; ++i) s += std::to_string(i * 0.005) + "," + std::to_string(std::sin(i * 1.3)) + "\n";
    return s;
  }());
  auto r = run_cli({"dev", file, "--rate", "200", "--column", "gyro", "--units", "deg/s"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("oadev [deg/s]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tau [s]"), std::string::npos) << r.out;
  r = run_cli({"dev", file, "--column", "gyro", "--time-column", "time", "--units", "deg/s",
               "--format", "csv", "--estimator", "tdev"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(",deg,"), std::string::npos) << r.out;  // tdev is an angle
  r = run_cli({"dev", file, "--column", "gyro", "--time-column", "time", "--units", "deg/s"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rate 200 Hz from the median interval"), std::string::npos) << r.out;
}

// Angle input (the integral of the rate) gives the rate-input curve, in the rate unit.
TEST(CliDev, AngleInputMatchesRateInput) {
  TempDir dir;
  std::vector<double> rate, angle{0.0};
  for (int i = 0; i < 3000; ++i) {
    rate.push_back(std::sin(0.71 * i) + 0.2 * std::cos(2.3 * i));
    angle.push_back(angle.back() + rate.back() * 0.01);
  }
  auto dev = [&](const std::string& name, const std::vector<double>& v, const char* kind, const char* unit) {
    const auto r = run_cli({"dev", dir.write(name, column_text(v)), "--rate", "100", "--input", kind,
                            "--units", unit, "--format", "json", "--no-ci", "--estimator", "ohdev"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto from_rate = dev("rate.txt", rate, "rate", "deg/s");
  const auto from_angle = dev("angle.txt", angle, "angle", "deg");
  EXPECT_EQ(from_angle["unit"], "deg/s");
  ASSERT_EQ(from_rate["points"].size(), from_angle["points"].size());
  for (std::size_t i = 0; i < from_rate["points"].size(); ++i) {
    // The text round trip of the angle (17 digits) and the mean removal differ by rounding.
    EXPECT_NEAR(from_angle["points"][i]["dev"].get<double>() / from_rate["points"][i]["dev"].get<double>(), 1.0, 1e-9);
  }
}

// The same physical record in deg/s and in deg/h must give the same curve, each in its unit.
TEST(CliDev, UnitsAndSensitivityScaleConsistently) {
  TempDir dir;
  std::vector<double> deg_s, deg_h, volts;
  for (int i = 0; i < 2000; ++i) {
    const double v = std::sin(0.37 * i) + 0.3 * std::cos(1.9 * i);
    deg_s.push_back(v);
    deg_h.push_back(v * 3600);
    volts.push_back(v * 0.02);  // 20 mV per deg/s, as the TG-100
  }
  auto dev_of = [&](const std::string& name, const std::vector<double>& values,
                    std::vector<std::string> extra) {
    std::vector<std::string> args{"dev", dir.write(name, column_text(values)), "--rate", "100",
                                  "--format", "json", "--no-ci"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto a = dev_of("a.txt", deg_s, {"--units", "deg/s"});
  const auto b = dev_of("b.txt", deg_h, {"--units", "deg/h"});
  const auto c = dev_of("c.txt", volts, {"--units", "deg/s", "--sensitivity", "0.02"});
  EXPECT_EQ(b["unit"], "deg/h");
  for (std::size_t i = 0; i < a["points"].size(); ++i) {
    const double dev = a["points"][i]["dev"];
    EXPECT_NEAR(b["points"][i]["dev"].get<double>() / 3600 / dev, 1.0, 1e-12);
    EXPECT_NEAR(c["points"][i]["dev"].get<double>() / dev, 1.0, 1e-12);
  }
}

TEST(CliDev, StandardInputAndBinaryChannels) {
  const auto y = test::nbs14_1000_point_frequency();
  auto r = run_cli({"dev", "-", "--rate", "1", "--af", "10", "--format", "csv", "--no-ci"}, column_text(y));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(",0.0915995"), std::string::npos) << r.out;

  TempDir dir;
  const std::string path = dir.file("two.bin");
  {
    std::ofstream out(path, std::ios::binary);
    for (double v : y) {
      const float pair[2] = {-1.0f, static_cast<float>(v)};
      out.write(reinterpret_cast<const char*>(pair), sizeof pair);
    }
  }
  r = run_cli({"dev", path, "--binary", "f32", "--channels", "2", "--column", "1", "--rate", "1",
               "--af", "10", "--format", "json", "--no-ci"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // f32 rounding of the samples (2^-24 relative) moves the deviation by far less than 1e-5.
  EXPECT_NEAR(nlohmann::json::parse(r.out)["points"][0]["dev"].get<double>() / 9.159953e-2, 1.0, 1e-5);
}

TEST(CliDev, NeverOverwritesWithoutForce) {
  TempDir dir;
  const auto in = dir.write("in.txt", column_text(test::nbs14_10_point_frequency()));
  const auto out = dir.write("result.txt", "precious");
  auto r = run_cli({"dev", in, "--rate", "1", "-o", out});
  expect_input_error(r, {"result.txt", "--force"});
  EXPECT_EQ(test::slurp(out), "precious");
  r = run_cli({"dev", in, "--rate", "1", "-o", out, "--force"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::slurp(out).find("oadev"), std::string::npos);
}

// A device or FIFO is not a file to protect, and a rename over it (the atomic write of a regular
// file) would replace /dev/null itself for a root user: such targets are written in place.
TEST(CliDev, WritesToDevNullInPlace) {
  TempDir dir;
  const auto in = dir.write("in.txt", column_text(test::nbs14_10_point_frequency()));
  for (const bool force : {false, true}) {
    std::vector<std::string> args{"dev", in, "--rate", "1", "-o", "/dev/null"};
    if (force) args.push_back("--force");
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_character_file("/dev/null"));
    EXPECT_FALSE(std::filesystem::exists("/dev/null.imunoise-tmp"));
  }
  const auto r = run_cli({"dev", in, "--rate", "1", "-o", dir.file("")});
  expect_input_error(r, {"is a directory"});
}

// ---- bad input: exit 1, a message naming where and how to fix, nothing on stdout ----

TEST(CliDevBadInput, EmptyFile) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("e.txt", ""), "--rate", "200"}), {"e.txt"});
}

TEST(CliDevBadInput, HeaderOnly) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("h.csv", "gyro_x\n"), "--rate", "200"}), {"h.csv"});
}

TEST(CliDevBadInput, RaggedRows) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("r.csv", "1,2\n3,4\n5\n6,7\n"), "--rate", "200", "--column", "0"}),
                     {"r.csv:3"});
}

TEST(CliDevBadInput, NonNumericCellNamesLineAndColumn) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("n.csv", "1,2\n3,4\n5,abc\n"), "--rate", "200", "--column", "1"}),
                     {"n.csv:3", "column 1", "abc"});
}

TEST(CliDevBadInput, NanAndInfSamples) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("nan.txt", "1\n2\nnan\n4\n5\n"), "--rate", "200"}), {"nan.txt:3"});
  expect_input_error(run_cli({"dev", dir.write("inf.txt", "1\n2\n3\n-inf\n5\n"), "--rate", "200"}), {"inf.txt:4"});
}

TEST(CliDevBadInput, TruncatedBinary) {
  TempDir dir;
  const std::string path = dir.write("t.f64", std::string(8 * 100 + 3, '\0'));
  expect_input_error(run_cli({"dev", path, "--rate", "200"}), {"t.f64", "trunc"});
}

TEST(CliDevBadInput, TauLongerThanDataNamesTheMaximum) {
  TempDir dir;
  const auto in = dir.write("in.txt", column_text(test::nbs14_1000_point_frequency()));
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--taus", "1,600"}), {"600 s", "maximum", "500 s"});
}

TEST(CliDevBadInput, ZeroOrNegativeRate) {
  TempDir dir;
  const auto in = dir.write("in.txt", column_text(test::nbs14_10_point_frequency()));
  expect_input_error(run_cli({"dev", in, "--rate", "0"}), {"rate"});
  expect_input_error(run_cli({"dev", in, "--rate", "-200"}), {"rate"});
  expect_input_error(run_cli({"dev", in}), {"--rate"});
  expect_input_error(run_cli({"dev", in, "--rate", "1e-300"}), {"outside", "Hz"});
}

TEST(CliDevBadInput, AbsurdScaleOverflows) {
  TempDir dir;
  const auto in = dir.write("in.txt", "1e300\n2e300\n-1e300\n1e300\n");
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--scale", "1e10"}), {"overflow", "--scale"});
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--scale", "0"}), {"--scale"});
}

TEST(CliDevBadInput, UnknownEstimatorUnitFormatAndLevel) {
  TempDir dir;
  const auto in = dir.write("in.txt", column_text(test::nbs14_10_point_frequency()));
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--estimator", "allan"}), {"allan", "oadev"});
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--units", "furlongs/fortnight"}), {"furlongs"});
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--format", "xml"}), {"xml"});
  expect_input_error(run_cli({"dev", in, "--rate", "1", "--ci", "1.5"}), {"--ci"});
}

TEST(CliDevBadInput, MissingFileAndAmbiguousColumns) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.file("nope.txt"), "--rate", "1"}), {"nope.txt"});
  expect_input_error(run_cli({"dev", dir.write("two.csv", "a,b\n1,2\n3,4\n"), "--rate", "1"}), {"--column"});
}

TEST(CliDevBadInput, TooFewSamples) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("one.txt", "1.0\n"), "--rate", "1"}), {"too few"});
}

TEST(CliDevBadInput, OutOfOrderAndGappyTimestamps) {
  TempDir dir;
  expect_input_error(run_cli({"dev", dir.write("o.csv", "t,g\n0,1\n1,2\n3,3\n2,4\n4,5\n5,6\n"), "--column", "g", "--time-column", "t"}),
                     {"o.csv:5"});
  std::string gappy = "t,g\n";
  for (int i = 0; i < 50; ++i) gappy += std::to_string(i < 20 ? i : i + 7) + ",1." + std::to_string(i) + "\n";
  expect_input_error(run_cli({"dev", dir.write("g.csv", gappy), "--column", "g", "--time-column", "t"}),
                     {"g.csv:22", "--allow-gaps"});
  const auto r = run_cli({"dev", dir.file("g.csv"), "--column", "g", "--time-column", "t", "--allow-gaps"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("gap"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imunoise

namespace imunoise {
namespace {

// Stable32 1.60 on PHASE.DAT (the NBS14 1000-point set integrated to phase), oadev with 68.3%
// bounds: m = 1: 2.8515e-01 .. 2.9987e-01; m = 128 (n = 745): 2.3045e-02 .. 3.7027e-02.
// Stable32 prints 5 digits, so agreement is checked to 1e-3 relative (its rounding is 2e-4).
TEST(CliDevConfidence, ReproducesStable32OnPhaseDat) {
  TempDir dir;
  const auto file = dir.write("nbs14.txt", column_text(test::nbs14_1000_point_frequency()));
  const auto r = run_cli({"dev", file, "--rate", "1", "--input", "freq", "--af", "1,128", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& p1 = j["points"][0];
  const auto& p128 = j["points"][1];
  EXPECT_NEAR(p1["dev"].get<double>() / 2.9223e-01, 1.0, 1e-3);
  EXPECT_NEAR(p1["ci_low"].get<double>() / 2.8515e-01, 1.0, 1e-3);
  EXPECT_NEAR(p1["ci_high"].get<double>() / 2.9987e-01, 1.0, 1e-3);
  EXPECT_EQ(p128["n"], 745);
  EXPECT_NEAR(p128["dev"].get<double>() / 2.7674e-02, 1.0, 1e-3);
  EXPECT_NEAR(p128["ci_low"].get<double>() / 2.3045e-02, 1.0, 1e-3);
  EXPECT_NEAR(p128["ci_high"].get<double>() / 3.7027e-02, 1.0, 1e-3);
  EXPECT_EQ(p1["alpha"], 0);  // white frequency noise (uniform deviates)
  EXPECT_GT(p1["edf"].get<double>(), 0.0);
}

TEST(CliDevConfidence, LevelAndForcedNoiseType) {
  TempDir dir;
  const auto file = dir.write("nbs14.txt", column_text(test::nbs14_1000_point_frequency()));
  auto width = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"dev", file, "--rate", "1", "--af", "16", "--format", "json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto p = nlohmann::json::parse(r.out)["points"][0];
    return std::pair{p["ci_high"].get<double>() - p["ci_low"].get<double>(), p["alpha"]};
  };
  const auto [w683, a683] = width({});
  const auto [w95, a95] = width({"--ci", "0.95"});
  EXPECT_GT(w95, w683);
  const auto [w_forced, a_forced] = width({"--noise-type", "-2"});
  EXPECT_EQ(a_forced, -2);
  EXPECT_EQ(width({"--noise-type", "FLFM"}).second, -1);
  expect_input_error(run_cli({"dev", file, "--rate", "1", "--noise-type", "7"}), {"7"});
  expect_input_error(run_cli({"dev", file, "--rate", "1", "--ci", "0"}), {"--ci"});
}

}  // namespace
}  // namespace imunoise

namespace imunoise::test {
namespace {

// A text file written by `imunoise simulate` states its rate in its header: `dev` uses it when
// neither --rate nor --time-column is given, says so on stderr, and --rate still overrides.
TEST(CliDevSimulatedFile, RateComesFromTheSimulateHeader) {
  TempDir dir;
  const auto file = dir.file("sim.txt");
  const auto sim = run_cli({"simulate", "--rate", "50", "--duration", "20", "--N", "0.01",
                            "--seed", "3", "-o", file});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto r = run_cli({"dev", file, "--af", "1", "--no-ci", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("rate 50 Hz from the file's imunoise simulate header"), std::string::npos)
      << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["rate_hz"].get<double>(), 50.0);
  EXPECT_EQ(j["points"][0]["tau_s"].get<double>(), 0.02);
  const auto forced = run_cli({"dev", file, "--rate", "100", "--af", "1", "--no-ci", "--format",
                               "json"});
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_EQ(nlohmann::json::parse(forced.out)["rate_hz"].get<double>(), 100.0);
  EXPECT_EQ(forced.err.find("header"), std::string::npos) << forced.err;
  // Any other text file still needs the rate.
  const auto plain = dir.write("plain.txt", "1\n2\n3\n4\n5\n");
  EXPECT_EQ(run_cli({"dev", plain}).exit_code, 1);
}

}  // namespace
}  // namespace imunoise::test
