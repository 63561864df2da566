// The preprocessing options through `imunoise dev`: each step is reported in the output (what
// was removed, how much), a gap is refused by default and pooled with --gaps split, spikes
// fail/report/reject, and a warm-up is found by --skip auto.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class PreprocessCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("imunoise_pre_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // t,gx at 100 Hz; gx = white(0.01) + extra(t). `drop` removes samples [drop_from, drop_from + drop).
  fs::path write(const std::string& name, std::size_t n, double (*extra)(double), std::size_t drop_from = 0,
                 std::size_t drop = 0, std::size_t spike_at = 0) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> g(0.0, 0.01);
    std::ofstream out(dir_ / name);
    out << "t,gx\n";
    char line[64];
    for (std::size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) / 100.0;
      double v = g(rng) + extra(t);
      if (spike_at != 0 && i == spike_at) v += 1.0;
      if (drop != 0 && i >= drop_from && i < drop_from + drop) continue;
      std::snprintf(line, sizeof line, "%.2f,%.9e\n", t, v);
      out << line;
    }
    return dir_ / name;
  }

  CliRun dev(const std::vector<std::string>& args) {
    std::string command = IMUNOISE_CLI_PATH;
    command += " dev";
    for (const auto& a : args) command += " '" + a + "'";
    command += " >" + (dir_ / "out").string() + " 2>" + (dir_ / "err").string();
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "out"), slurp(dir_ / "err")};
  }

  fs::path dir_;
};

double none(double) { return 0.0; }
double warm_up_and_drift(double t) { return 0.05 * std::exp(-t / 60.0) + 2e-6 * t; }

TEST_F(PreprocessCli, WarmUpSkippedAutomaticallyAndDriftRemovedAreReported) {
  const auto file = write("warm.csv", 120'000, warm_up_and_drift);
  const CliRun r = dev({file.string(), "--time-column", "t", "--column", "gx", "--units", "rad/s", "--skip", "auto",
                     "--detrend", "linear", "--davar", "--format", "json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& pre = j.at("preprocessing");
  ASSERT_GE(pre.size(), 3u);
  const std::string skip = pre[0];
  EXPECT_NE(skip.find("flags a warm-up"), std::string::npos) << skip;
  EXPECT_LT(j.at("n_samples").get<std::size_t>(), 120'000u);
  const std::string detrend = pre[1];
  EXPECT_NE(detrend.find("detrend linear: removed c0 = "), std::string::npos) << detrend;
  EXPECT_NE(detrend.find("biases rate random walk K"), std::string::npos) << detrend;
  // After the skip and the detrend what is left is white noise: DAVAR calls it stationary.
  EXPECT_TRUE(j.at("davar").at("stationary").get<bool>()) << pre[2];
  EXPECT_EQ(j.at("davar").at("avar_si").size(), j.at("davar").at("window_start_s").size());
}

TEST_F(PreprocessCli, GapRefusedByDefaultAndPooledWithGapsSplit) {
  const auto file = write("gap.csv", 60'000, none, 30'000, 500);  // 5 s missing
  const CliRun refused = dev({file.string(), "--time-column", "t", "--column", "gx"});
  EXPECT_EQ(refused.code, 1);
  EXPECT_NE(refused.err.find("gap"), std::string::npos) << refused.err;
  const CliRun split = dev({file.string(), "--time-column", "t", "--column", "gx", "--gaps", "split", "--format", "json"});
  ASSERT_EQ(split.code, 0) << split.err;
  const auto j = nlohmann::json::parse(split.out);
  EXPECT_EQ(j.at("n_samples").get<std::size_t>(), 59'500u);
  EXPECT_NE(j.at("note").get<std::string>().find("pooled over 2 segments"), std::string::npos);
  EXPECT_NE(j.at("preprocessing")[0].get<std::string>().find("1 gaps; analysed as 2 segments"), std::string::npos);
  // White noise of 0.01 at 100 Hz: oadev(tau = 0.01 s) = 0.01, within the pooled bounds.
  const auto& p0 = j.at("points")[0];
  EXPECT_LE(p0.at("ci_low").get<double>(), 0.01);
  EXPECT_GE(p0.at("ci_high").get<double>(), 0.01);
  // The whole Allan family pools (mdev here); the total family cannot and says why.
  const CliRun mdev = dev({file.string(), "--time-column", "t", "--column", "gx", "--gaps", "split", "--estimator",
                           "mdev,hdev", "--format", "json"});
  ASSERT_EQ(mdev.code, 0) << mdev.err;
  const auto curves = nlohmann::json::parse(mdev.out);
  ASSERT_EQ(curves.size(), 2u);
  EXPECT_EQ(curves[0].at("estimator"), "mdev");
  EXPECT_NE(curves[1].at("note").get<std::string>().find("pooled over 2 segments"), std::string::npos);
  const CliRun other = dev({file.string(), "--time-column", "t", "--column", "gx", "--gaps", "split", "--estimator", "totdev"});
  EXPECT_EQ(other.code, 1);
  EXPECT_NE(other.err.find("totdev cannot be pooled over them: the total family extends the record by reflection"),
            std::string::npos) << other.err;
  EXPECT_NE(other.err.find("fix: --estimator adev, oadev, mdev"), std::string::npos) << other.err;
}

TEST_F(PreprocessCli, SpikesFailReportReject) {
  const auto file = write("spike.csv", 20'000, none, 0, 0, 12'345);
  const CliRun fail = dev({file.string(), "--time-column", "t", "--column", "gx", "--outliers", "fail"});
  EXPECT_EQ(fail.code, 1);
  EXPECT_NE(fail.err.find("1 spikes"), std::string::npos) << fail.err;
  EXPECT_NE(fail.err.find("12345"), std::string::npos) << fail.err;
  const CliRun report = dev({file.string(), "--time-column", "t", "--column", "gx", "--outliers", "report"});
  EXPECT_EQ(report.code, 0) << report.err;
  EXPECT_NE(report.out.find("# preprocessing: outliers report: 1 spikes"), std::string::npos) << report.out;
  const CliRun reject = dev({file.string(), "--time-column", "t", "--column", "gx", "--outliers", "reject", "--format", "json"});
  ASSERT_EQ(reject.code, 0) << reject.err;
  EXPECT_EQ(nlohmann::json::parse(reject.out).at("n_samples").get<std::size_t>(), 19'999u);
}

}  // namespace

namespace {

TEST_F(PreprocessCli, TemperatureBinsReportedPerBin) {
  std::ofstream out(dir_ / "temp.csv");
  out << "t,gx,temp_c\n";
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 0.01);
  char line[96];
  for (std::size_t i = 0; i < 40'000; ++i) {
    const double t = static_cast<double>(i) / 100.0;
    const double temp = 20.0 + 10.0 * static_cast<double>(i) / 40'000.0;  // 20 -> 30 degC
    std::snprintf(line, sizeof line, "%.2f,%.9e,%.4f\n", t, 0.1 + 0.01 * (temp - 20.0) + g(rng), temp);
    out << line;
  }
  out.close();
  const CliRun r = dev({(dir_ / "temp.csv").string(), "--time-column", "t", "--column", "gx", "--temperature",
                        "temp_c", "--temperature-bin", "5", "--format", "json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto bins = nlohmann::json::parse(r.out).at("temperature_bins");
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_EQ(bins[0].at("low").get<double>(), 20.0);
  EXPECT_EQ(bins[1].at("low").get<double>(), 25.0);
  for (const auto& b : bins) {
    const double expected = 0.1 + 0.01 * (b.at("mean_temperature").get<double>() - 20.0);
    EXPECT_NEAR(b.at("bias_si").get<double>(), expected, 5 * b.at("bias_stderr_si").get<double>());
  }
}

}  // namespace

namespace {

TEST_F(PreprocessCli, FitReportsPreprocessingAndKeepsItsSourceField) {
  const auto file = write("fit.csv", 60'000, warm_up_and_drift);
  std::string command = std::string(IMUNOISE_CLI_PATH) + " fit '" + file.string() +
                        "' --time-column t --column gx --units rad/s --skip 60 --detrend linear --format json >" +
                        (dir_ / "out").string() + " 2>" + (dir_ / "err").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << slurp(dir_ / "err");
  const auto j = nlohmann::json::parse(slurp(dir_ / "out"));
  EXPECT_EQ(j.at("source").get<std::string>(), file.string());
  ASSERT_EQ(j.at("preprocessing").size(), 2u);
  EXPECT_EQ(j.at("preprocessing")[0].get<std::string>(), "skip: removed the first 60 s (6000 samples)");
}

}  // namespace
