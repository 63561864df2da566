// One record over several ranks (`dev --mpi`, `fit --mpi` under mpirun -np 2 and 3): each rank
// reads its slice (3 ranks: uneven slices), the merged curves equal the serial ones to 1e-12
// relative (the terms are the same; only the order of the additions and the integration
// origin of each slice differ: ~1e-15 observed), and bad input stops every rank with the
// file's message instead of hanging.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>

#include "fleet/mpi_runner.hpp"

namespace imunoise::test {
namespace {

constexpr double kRelative = 1e-12;
const std::string kAll = "adev,oadev,mdev,tdev,hdev,ohdev";

// 30011 rate samples (prime: no rank count divides it) of white + random-walk noise on a
// large offset, as raw f64.
std::string write_record(const TempDir& dir, const std::string& name, std::size_t n = 30011) {
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal;
  std::vector<double> y(n);
  double walk = 0.0;
  for (auto& v : y) {
    walk += 0.01 * normal(engine);
    v = 250.0 + normal(engine) + walk;
  }
  std::string bytes(n * sizeof(double), '\0');
  std::memcpy(bytes.data(), y.data(), bytes.size());
  return dir.write(name, bytes);
}

void expect_same_curves(const std::string& serial, const std::string& parallel) {
  const auto a = nlohmann::json::parse(serial);
  const auto b = nlohmann::json::parse(parallel);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t c = 0; c < a.size(); ++c) {
    ASSERT_EQ(a[c]["estimator"], b[c]["estimator"]);
    ASSERT_EQ(a[c]["points"].size(), b[c]["points"].size());
    EXPECT_EQ(a[c]["n_samples"], b[c]["n_samples"]);
    for (std::size_t i = 0; i < a[c]["points"].size(); ++i) {
      const auto& p = a[c]["points"][i];
      const auto& q = b[c]["points"][i];
      EXPECT_EQ(p["m"], q["m"]);
      EXPECT_EQ(p["n"], q["n"]) << a[c]["estimator"] << " m=" << p["m"];
      EXPECT_NEAR(q["dev"].get<double>() / p["dev"].get<double>(), 1.0, kRelative)
          << a[c]["estimator"] << " m=" << p["m"];
    }
  }
}

class MpiRanks : public ::testing::TestWithParam<int> {};

TEST_P(MpiRanks, DevOfBinarySlicesEqualsSerial) {
  IMUNOISE_REQUIRE_MPI();
  TempDir dir;
  const auto file = write_record(dir, "gyro.f64");
  const auto serial = run_cli({"dev", file, "--rate", "100", "--no-ci", "--estimator", kAll,
                               "--taus", "perdecade:20", "--format", "json"});
  ASSERT_EQ(serial.exit_code, 0) << serial.err;
  const auto parallel = run_mpi(GetParam(), {"dev", file, "--rate", "100", "--mpi", "--estimator",
                                             kAll, "--taus", "perdecade:20", "--format", "json"});
  ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
  expect_same_curves(serial.out, parallel.out);
}

TEST_P(MpiRanks, DevOfAngleInputAndTextEqualsSerial) {
  IMUNOISE_REQUIRE_MPI();
  TempDir dir;
  const auto file = write_record(dir, "angle.f64", 5003);
  for (const std::vector<std::string> input :
       {std::vector<std::string>{file, "--input", "angle", "--units", "deg"},
        std::vector<std::string>{}}) {
    std::vector<std::string> args = input;
    if (args.empty()) {  // text: rank 0 reads and sends the slices
      std::string text;
      const auto raw = slurp(file);
      for (std::size_t i = 0; i < raw.size(); i += 8) {
        double v;
        std::memcpy(&v, raw.data() + i, 8);
        text += std::to_string(v) + "\n";
      }
      args = {dir.write("rate.txt", text), "--units", "deg/s"};
    }
    for (const auto& a : std::vector<std::string>{"--rate", "50", "--estimator", kAll, "--format", "json"}) {
      args.push_back(a);
    }
    auto serial_args = args;
    serial_args.insert(serial_args.begin(), "dev");
    serial_args.push_back("--no-ci");
    auto mpi_args = args;
    mpi_args.insert(mpi_args.begin(), "dev");
    mpi_args.push_back("--mpi");
    const auto serial = run_cli(serial_args);
    ASSERT_EQ(serial.exit_code, 0) << serial.err;
    const auto parallel = run_mpi(GetParam(), mpi_args);
    ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
    expect_same_curves(serial.out, parallel.out);
  }
}

TEST_P(MpiRanks, FitOfSlicesEqualsSerial) {
  IMUNOISE_REQUIRE_MPI();
  TempDir dir;
  const auto file = write_record(dir, "gyro.f64", 100003);
  const auto serial = run_cli({"fit", file, "--rate", "100", "--units", "deg/s"});
  ASSERT_EQ(serial.exit_code, 0) << serial.err;
  const auto parallel = run_mpi(GetParam(), {"fit", file, "--rate", "100", "--units", "deg/s", "--mpi"});
  ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
  const auto a = nlohmann::json::parse(serial.out);
  const auto b = nlohmann::json::parse(parallel.out);
  int compared = 0;
  for (const char* term : {"Q", "N", "B", "K"}) {
    const auto& p = a["terms"][term];
    const auto& q = b["terms"][term];
    EXPECT_EQ(p["identified"], q["identified"]) << term;
    if (p["value"].get<double>() > 0.0) {
      // The fit is a smooth function of the curve, which agrees to ~1e-15.
      EXPECT_NEAR(q["value"].get<double>() / p["value"].get<double>(), 1.0, 1e-9) << term;
      ++compared;
    }
  }
  EXPECT_GE(compared, 2);
}

TEST_P(MpiRanks, BadSampleInOneSliceStopsEveryRankWithTheRecord) {
  IMUNOISE_REQUIRE_MPI();
  TempDir dir;
  const auto file = write_record(dir, "bad.f64", 9001);
  auto bytes = slurp(file);
  const double nan = std::nan("");
  std::memcpy(bytes.data() + 8000 * 8, &nan, 8);  // in the last rank's slice
  dir.write("bad.f64", bytes);
  const auto r = run_mpi(GetParam(), {"dev", file, "--rate", "100", "--mpi"}, 60);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("record 8000"), std::string::npos) << r.err;
}

// Intervals under --mpi: the noise type is identified on rank 0's slice, the EDF counts the
// whole record. Where the slice gives the serial run's noise type, EDF and bounds equal the
// serial ones (the EDF is a function of alpha, m and N only); white + random-walk FM has a clear
// type at almost every tau, so most taus must agree, and each disagreement is a neighbouring type.
TEST_P(MpiRanks, DevIntervalsCountTheWholeRecord) {
  IMUNOISE_REQUIRE_MPI();
  TempDir dir;
  const auto file = write_record(dir, "gyro.f64", 100003);
  const auto serial = run_cli({"dev", file, "--rate", "100", "--estimator", "oadev,mdev",
                               "--format", "json"});
  ASSERT_EQ(serial.exit_code, 0) << serial.err;
  const auto parallel = run_mpi(GetParam(), {"dev", file, "--rate", "100", "--mpi", "--estimator",
                                             "oadev,mdev", "--format", "json"});
  ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
  const auto a = nlohmann::json::parse(serial.out);
  const auto b = nlohmann::json::parse(parallel.out);
  ASSERT_EQ(a.size(), b.size());
  std::size_t points = 0, same_type = 0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    for (std::size_t i = 0; i < a[c]["points"].size(); ++i) {
      const auto& p = a[c]["points"][i];
      const auto& q = b[c]["points"][i];
      ++points;
      ASSERT_FALSE(q["edf"].is_null()) << "m=" << q["m"];
      EXPECT_LE(std::abs(p["alpha"].get<int>() - q["alpha"].get<int>()), 1) << "m=" << p["m"];
      if (p["alpha"] != q["alpha"]) continue;
      ++same_type;
      EXPECT_NEAR(q["edf"].get<double>() / p["edf"].get<double>(), 1.0, 1e-12) << "m=" << p["m"];
      EXPECT_NEAR(q["ci_low"].get<double>() / p["ci_low"].get<double>(), 1.0, 1e-9);
      EXPECT_NEAR(q["ci_high"].get<double>() / p["ci_high"].get<double>(), 1.0, 1e-9);
    }
  }
  EXPECT_GE(static_cast<double>(same_type), 0.8 * static_cast<double>(points))
      << same_type << " of " << points << " taus";
}

INSTANTIATE_TEST_SUITE_P(Fleet, MpiRanks, ::testing::Values(2, 3));

TEST(MpiRecord, PlainRunIntervalsEqualSerial) {
  TempDir dir;
  const auto file = write_record(dir, "gyro.f64");
  const auto serial = run_cli({"dev", file, "--rate", "100", "--estimator", kAll, "--format", "json"});
  const auto single = run_cli({"dev", file, "--rate", "100", "--mpi", "--estimator", kAll,
                               "--format", "json"});
  ASSERT_EQ(serial.exit_code, 0) << serial.err;
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const auto a = nlohmann::json::parse(serial.out);
  const auto b = nlohmann::json::parse(single.out);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t c = 0; c < a.size(); ++c) {
    ASSERT_EQ(a[c]["points"].size(), b[c]["points"].size());
    for (std::size_t i = 0; i < a[c]["points"].size(); ++i) {
      const auto& p = a[c]["points"][i];
      const auto& q = b[c]["points"][i];
      EXPECT_EQ(p["alpha"], q["alpha"]) << a[c]["estimator"] << " m=" << p["m"];
      EXPECT_EQ(p["edf"], q["edf"]) << a[c]["estimator"] << " m=" << p["m"];
      EXPECT_NEAR(q["ci_high"].get<double>() / p["ci_high"].get<double>(), 1.0, kRelative);
    }
  }
}

TEST(MpiRecord, PlainRunWithMpiFlagIsOneRank) {
  TempDir dir;
  const auto file = write_record(dir, "gyro.f64");
  const auto serial = run_cli({"dev", file, "--rate", "100", "--no-ci", "--estimator", kAll, "--format", "json"});
  const auto single = run_cli({"dev", file, "--rate", "100", "--mpi", "--estimator", kAll, "--format", "json"});
  ASSERT_EQ(single.exit_code, 0) << single.err;
  expect_same_curves(serial.out, single.out);
}

TEST(MpiRecord, NonMergeableEstimatorIsRefused) {
  TempDir dir;
  const auto file = write_record(dir, "gyro.f64", 1000);
  const auto r = run_cli({"dev", file, "--rate", "100", "--mpi", "--estimator", "totdev"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("totdev cannot be split"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace imunoise::test
