// `imunoise fleet` serial and under mpirun -np 2 / 3: byte-identical outputs, keep-going and
// --strict, a rank that dies ends the run (no hang), mixed rates, outputs never overwritten.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "fleet/mpi_runner.hpp"

namespace imunoise::test {
namespace {

// Six gyros of one batch (white noise N near 7e-4 deg/sqrt(s) = 0.042 deg/sqrt(h), one at
// 9.5e-4), a seventh at another rate with N = 4e-3, and a file that is not a record.
struct Fleet {
  TempDir dir;
  std::vector<std::string> files;
  Fleet() {
    const double n[] = {7.0e-4, 7.2e-4, 6.9e-4, 9.5e-4, 7.1e-4, 6.8e-4};
    for (int i = 0; i < 6; ++i) {
      const std::string file = dir.file("s" + std::to_string(i + 1) + ".txt");
      const auto r = run_cli({"simulate", "--rate", "100", "--duration", "1200", "--N",
                              std::to_string(n[i]), "--B", "0.0003", "--K", "2e-6", "--seed",
                              std::to_string(i + 1), "-o", file});
      EXPECT_EQ(r.exit_code, 0) << r.err;
      files.push_back(file);
      if (i == 2) {
        files.push_back(dir.write("broken.txt", "0.1\n0.2\nnot-a-number\n"));
      }
    }
    const std::string odd = dir.file("odd50hz.txt");
    const auto r = run_cli({"simulate", "--rate", "50", "--duration", "1200", "--N", "0.004",
                            "--B", "0.0003", "--seed", "11", "-o", odd});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    files.push_back(odd);
  }
  /// One fleet for every test (its files are only read; each test writes its own outputs).
  static const Fleet& shared() {
    static const Fleet fleet;
    return fleet;
  }
  std::vector<std::string> args(const std::string& out, std::vector<std::string> extra = {}) const {
    std::vector<std::string> a{"fleet"};
    a.insert(a.end(), files.begin(), files.end());
    for (const auto& s : {"--units", "deg/s", "--spec", "tg100", "-o"}) a.emplace_back(s);
    a.push_back(out);
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
};

TEST(FleetCli, SerialRunReportsDistributionsOutliersAndGoesOnPastABadFile) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  const auto r = run_cli(fleet.args(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("broken.txt:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the fleet run goes on"), std::string::npos);
  const auto doc = nlohmann::json::parse(slurp(out + "/fleet.json"));
  ASSERT_EQ(doc["sensors"].size(), 8u);
  EXPECT_EQ(doc["summary"]["n_failed"], 1);
  EXPECT_EQ(doc["sensors"][3]["flags"], nlohmann::json({"error"}));
  // Mixed rates: each file at its own rate (from its header).
  EXPECT_EQ(doc["summary"]["rates_hz"], nlohmann::json({50.0, 100.0}));
  EXPECT_EQ(doc["sensors"][7]["fit"]["rate_hz"], 50.0);
  // The 9.5e-4 gyro (0.057 deg/sqrt(h)) and the 4e-3 one are outliers on N and fail the
  // datasheet's 0.05 deg/sqrt(h); the batch's typical gyros pass.
  for (const int i : {4, 7}) {
    const auto& flags = doc["sensors"][i]["flags"];
    EXPECT_NE(std::find(flags.begin(), flags.end(), "outlier"), flags.end()) << i;
    EXPECT_NE(std::find(flags.begin(), flags.end(), "datasheet_fail"), flags.end()) << i;
    EXPECT_NE(doc["sensors"][i]["reasons"][0].get<std::string>().find("N = "), std::string::npos);
  }
  for (const int i : {1, 2, 5, 6}) EXPECT_TRUE(doc["sensors"][i]["flags"].empty()) << i << doc["sensors"][i]["flags"];
  const auto& n = doc["summary"]["coefficients"]["N"];
  EXPECT_EQ(n["n_identified"], 7);
  EXPECT_NEAR(n["distribution"]["median"].get<double>(), 7.1e-4, 0.03 * 7.1e-4);
  EXPECT_GT(doc["summary"]["datasheet"]["pass_rate"].get<double>(), 0.5);
  const std::string csv = slurp(out + "/fleet.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
  // Nothing is overwritten without --force.
  const auto again = run_cli(fleet.args(out));
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("fleet.json: file exists"), std::string::npos) << again.err;
  EXPECT_EQ(run_cli(fleet.args(out, {"--force"})).exit_code, 0);
}

TEST(FleetCli, StrictStopsAtTheFirstBadFile) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto r = run_cli(fleet.args(out_dir.file("out"), {"--strict"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.txt:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--strict"), std::string::npos) << r.err;
}

class FleetRanks : public ::testing::TestWithParam<int> {};

TEST_P(FleetRanks, OutputsAreTheSerialRunsBytes) {
  IMUNOISE_REQUIRE_MPI();
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto serial = run_cli(fleet.args(out_dir.file("serial")));
  ASSERT_EQ(serial.exit_code, 0) << serial.err;
  const auto parallel = run_mpi(GetParam(), fleet.args(out_dir.file("parallel")));
  ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
  EXPECT_EQ(slurp(out_dir.file("parallel/fleet.json")), slurp(out_dir.file("serial/fleet.json")));
  EXPECT_EQ(slurp(out_dir.file("parallel/fleet.csv")), slurp(out_dir.file("serial/fleet.csv")));
  EXPECT_NE(parallel.err.find("broken.txt:3"), std::string::npos) << parallel.err;
}

TEST_P(FleetRanks, StrictStopsEveryRank) {
  IMUNOISE_REQUIRE_MPI();
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto r = run_mpi(GetParam(), fleet.args(out_dir.file("out"), {"--strict"}), 60);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("broken.txt:3"), std::string::npos) << r.err;
}

TEST_P(FleetRanks, ARankThatDiesFailsTheRunWithoutHanging) {
  IMUNOISE_REQUIRE_MPI();
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto r = run_mpi(GetParam(), fleet.args(out_dir.file("out")), 60,
                         "IMUNOISE_TEST_RANK_DIES_ON=s5.txt");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 124) << "the run hung";
  // mpirun names the rank that died and the signal.
  EXPECT_NE(r.err.find("signal 9"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out_dir.file("out/fleet.json")));
}

INSTANTIATE_TEST_SUITE_P(Fleet, FleetRanks, ::testing::Values(2, 3));

}  // namespace
}  // namespace imunoise::test
