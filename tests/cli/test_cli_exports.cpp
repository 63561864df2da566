// --export TARGET[:FILE] and --inflate on fit and analyze, as a user runs them: the files
// appear where asked (or under default names in -o DIR), fit's JSON lists them, a six-channel
// analyze gives gyro AND accelerometer values, and bad requests fail before any work.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace imunoise {
namespace {

using test::run_cli;
using test::slurp;
using test::TempDir;

std::string simulate(const TempDir& dir, const std::string& name, const std::string& units, const std::string& n,
                     const std::string& channels, const std::string& seed, const std::string& k = "1e-3") {
  const std::string file = dir.file(name);
  const auto sim = run_cli({"simulate", "--rate", "100", "--duration", "600", "--N", n, "--K", k, "--units",
                            units, "--channels", channels, "--seed", seed, "-o", file});
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  return file;
}

TEST(CliExports, FitWritesEachTargetAndStatesTheInflation) {
  TempDir dir;
  const auto g = simulate(dir, "g.txt", "deg/s", "0.01", "1", "3");
  const std::string params = dir.file("ekf.params");
  const std::string vins = dir.file("vins.yaml");
  const auto r = run_cli({"fit", g, "--rate", "100", "--units", "deg/s", "--export", "px4:" + params, "--export",
                          "vins:" + vins, "--inflate", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["exports"].size(), 2u);
  EXPECT_EQ(j["exports"][0]["target"], "px4");
  EXPECT_EQ(j["exports"][0]["path"], params);
  EXPECT_EQ(j["exports"][1]["inflation"].get<double>(), 2.0);
  const std::string text = slurp(vins);
  EXPECT_NE(text.find("inflation factor: 2.0"), std::string::npos);
  // gyr_n = 2 x N sqrt(100 Hz), N from the fit in rad/s/sqrt(Hz).
  const double n = j["terms"]["N"]["value"].get<double>() * M_PI / 180.0;
  const auto at = text.find("gyr_n: ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(text.substr(at + 7)), 2.0 * n * 10.0, 1e-12 * n);
  // The accelerometer was not measured: placeholders, never numbers.
  EXPECT_NE(text.find("# acc_n: <FILL IN>"), std::string::npos);
  EXPECT_NE(slurp(params).find("EKF2_GYR_NOISE\t"), std::string::npos);

  // --inflation is the old spelling of --inflate; --kalibr keeps working beside --export.
  const auto old = run_cli({"fit", g, "--rate", "100", "--units", "deg/s", "--kalibr", dir.file("k.yaml"),
                            "--inflation", "3", "--export", "ros:" + dir.file("ros.yaml")});
  ASSERT_EQ(old.exit_code, 0) << old.err;
  EXPECT_NE(slurp(dir.file("k.yaml")).find("inflation factor: 3.0"), std::string::npos);
  EXPECT_NE(slurp(dir.file("ros.yaml")).find("inflation factor: 3.0"), std::string::npos);
}

TEST(CliExports, BadRequestsFailBeforeTheWork) {
  TempDir dir;
  const auto g = simulate(dir, "g.txt", "deg/s", "0.01", "1", "3");
  const auto unknown = run_cli({"fit", g, "--rate", "100", "--units", "deg/s", "--export", "rovio"});
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("unknown target 'rovio'; targets: kalibr openvins vins orbslam3 gtsam px4 matlab ros"),
            std::string::npos)
      << unknown.err;
  const std::string existing = dir.write("x.params", "mine\n");
  const auto kept = run_cli({"fit", g, "--rate", "100", "--units", "deg/s", "--export", "px4:" + existing});
  EXPECT_EQ(kept.exit_code, 1);
  EXPECT_NE(kept.err.find("file exists"), std::string::npos) << kept.err;
  EXPECT_EQ(slurp(existing), "mine\n");
  // Without a unit the values are not SI: no filter file.
  const auto unitless = run_cli({"fit", g, "--rate", "100", "--export", "ros:" + dir.file("r.yaml")});
  EXPECT_EQ(unitless.exit_code, 1);
  EXPECT_NE(unitless.err.find("--units"), std::string::npos) << unitless.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("r.yaml")));
  // An accelerometer alone cannot make a Kalibr file (its gyro keys come first).
  const auto a = simulate(dir, "a.txt", "m/s^2", "0.002", "1", "4");
  const auto kalibr = run_cli({"fit", a, "--rate", "100", "--units", "m/s^2", "--export", "kalibr:" + dir.file("k.yaml")});
  EXPECT_EQ(kalibr.exit_code, 1);
  EXPECT_NE(kalibr.err.find("no gyroscope channel"), std::string::npos) << kalibr.err;
}

TEST(CliExports, AnalyzeOfSixChannelsGivesGyroAndAccelerometer) {
  TempDir dir;
  const auto g = simulate(dir, "g.txt", "deg/s", "0.01", "3", "5");
  const auto a = simulate(dir, "a.txt", "m/s^2", "0.002", "3", "6", "2e-4");
  const std::string rep = dir.file("rep");
  const auto r = run_cli({"analyze", g, a, "--rate", "100", "--units", "deg/s,deg/s,deg/s,m/s^2,m/s^2,m/s^2", "-q",
                          "-o", rep, "--export", "orbslam3", "--export", "gtsam", "--export", "matlab"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"orbslam3_imu.yaml", "gtsam_imu.json", "gtsam_imu.py", "imunoise_imu_params.m"}) {
    EXPECT_TRUE(std::filesystem::exists(rep + "/" + f)) << f;
    EXPECT_NE(r.out.find(f), std::string::npos) << r.out;
  }
  const std::string orb = slurp(rep + "/orbslam3_imu.yaml");
  EXPECT_EQ(orb.find("<FILL IN>"), std::string::npos) << orb;
  EXPECT_NE(orb.find("per term the largest of 3 axes"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(rep + "/gtsam_imu.json"));
  // The simulated accelerometer white noise: N = 0.002 m/s^2/sqrt(Hz), so N^2 = 4e-6 (+- a few %).
  EXPECT_NEAR(j["accelerometerCovariance"][0][0].get<double>(), 4e-6, 0.4e-6);
  const double n_gyro = 0.01 * M_PI / 180.0;
  EXPECT_NEAR(j["gyroscopeCovariance"][1][1].get<double>(), n_gyro * n_gyro, 0.1 * n_gyro * n_gyro);
  // Existing export files in DIR are kept without --force (the report's own check comes first).
  const auto again = run_cli({"analyze", g, a, "--rate", "100", "--units", "deg/s,deg/s,deg/s,m/s^2,m/s^2,m/s^2",
                              "-q", "-o", rep, "--export", "orbslam3"});
  EXPECT_EQ(again.exit_code, 1);
}

}  // namespace
}  // namespace imunoise

namespace imunoise {
namespace {

using test::run_cli;
using test::slurp;
using test::TempDir;

TEST(CliCheck, ExportedFileIsConsistentAndAMistakeExitsOne) {
  TempDir dir;
  const auto g = simulate(dir, "g.txt", "deg/s", "0.01", "1", "3");
  const std::string vins = dir.file("vins.yaml");
  ASSERT_EQ(run_cli({"fit", g, "--rate", "100", "--units", "deg/s", "--export", "vins:" + vins}).exit_code, 0);
  const auto good = run_cli({"check", vins, g, "--rate", "100", "--units", "deg/s", "--format", "json"});
  ASSERT_EQ(good.exit_code, 0) << good.err << good.out;
  const auto j = nlohmann::json::parse(good.out);
  EXPECT_EQ(j["target"], "vins");
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_EQ(j["values"][0]["key"], "gyr_n");
  EXPECT_EQ(j["values"][0]["verdict"], "consistent");
  EXPECT_EQ(j["values"][1]["key"], "gyr_w");
  // acc_n / acc_w are placeholders in the file (the record has no accelerometer): not checked.
  ASSERT_EQ(j["values"].size(), 2u);
  EXPECT_EQ(j["notes"][0], "acc_n is not in the file (not checked)");
  // The same record's Kalibr density written into the VINS file: the classic mistake.
  const std::string kalibr = dir.file("k.yaml");
  ASSERT_EQ(run_cli({"fit", g, "--rate", "100", "--units", "deg/s", "--export", "kalibr:" + kalibr}).exit_code, 0);
  const std::string k = slurp(kalibr);
  const auto at = k.find("\ngyroscope_noise_density: ");
  ASSERT_NE(at, std::string::npos);
  const std::string density = k.substr(at + 26, k.find(' ', at + 26) - at - 26);
  const std::string wrong = dir.write("wrong.yaml", "%YAML:1.0\ngyr_n: " + density + "\n");
  const auto bad = run_cli({"check", wrong, g, "--rate", "100", "--units", "deg/s"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.out.find("WRONG by / sqrt(rate)"), std::string::npos) << bad.out;
  const auto unknown = run_cli({"check", wrong, g, "--rate", "100", "--units", "deg/s", "--target", "msckf"});
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("unknown target 'msckf'; targets: kalibr"), std::string::npos) << unknown.err;
  const auto unrecognised = run_cli({"check", g, g, "--rate", "100", "--units", "deg/s"});
  EXPECT_EQ(unrecognised.exit_code, 1);
  EXPECT_NE(unrecognised.err.find("give --target T"), std::string::npos) << unrecognised.err;
}

}  // namespace
}  // namespace imunoise
