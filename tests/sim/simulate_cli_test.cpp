// `imunoise simulate` end to end: header, reproducibility, formats, no overwrite, bad input.
// Skipped when the CLI has not been built (the sim test target does not build it).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

struct CliResult {
  int status = -1;
  std::string err;
};

class SimulateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    cli_ = IMUNOISE_CLI_PATH;
    if (!fs::exists(cli_)) GTEST_SKIP() << "imunoise CLI not built: " << cli_;
    dir_ = fs::temp_directory_path() /
           ("imunoise_sim_cli_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    if (!dir_.empty()) fs::remove_all(dir_, ignored);
  }
  CliResult run(const std::string& args) {
    const fs::path err = dir_ / "stderr.txt";
    const std::string command = "\"" + cli_ + "\" simulate " + args + " 2>\"" + err.string() + "\"";
    CliResult r;
    const int raw = std::system(command.c_str());
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.err = slurp(err);
    return r;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::string path(const char* name) const { return (dir_ / name).string(); }

  std::string cli_;
  fs::path dir_;
};

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_F(SimulateCli, PresetTextHasHeaderNamesAndRows) {
  const CliResult r = run("--preset tg100 --duration 2 --seed 5 -o " + path("tg.txt"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto text = lines(slurp(path("tg.txt")));
  std::size_t comments = 0;
  while (comments < text.size() && text[comments].starts_with("#")) ++comments;
  ASSERT_GT(comments, 4U);
  EXPECT_NE(text[0].find("preset tg100"), std::string::npos);
  EXPECT_NE(text[1].find("rate_hz 200"), std::string::npos);
  EXPECT_NE(text[1].find("seed 5"), std::string::npos);
  EXPECT_NE(slurp(path("tg.txt")).find("gyro1: N 0.00089 deg/sqrt(s), B 0.00059 deg/s"), std::string::npos);
  EXPECT_EQ(text[comments], "gyro1\tgyro2\tgyro3\tgyro4");
  EXPECT_EQ(text.size() - comments - 1, 400U);  // 2 s at 200 Hz
  std::istringstream row(text[comments + 1]);
  double a, b, c, d;
  EXPECT_TRUE(row >> a >> b >> c >> d);
}

TEST_F(SimulateCli, ReproducibleAcrossRunsAndThreads) {
  const std::string model = "--rate 100 --duration 30 --N 1e-3 --B 5e-4 --K 1e-5 --channels 3 --seed 9 ";
  ASSERT_EQ(run(model + "--threads 1 -o " + path("a.txt")).status, 0);
  ASSERT_EQ(run(model + "--threads 3 -o " + path("b.txt")).status, 0);
  EXPECT_EQ(slurp(path("a.txt")), slurp(path("b.txt")));
  ASSERT_EQ(run("--rate 100 --duration 30 --N 1e-3 --B 5e-4 --K 1e-5 --channels 3 --seed 10 -o " +
                path("c.txt")).status, 0);
  EXPECT_NE(slurp(path("a.txt")), slurp(path("c.txt")));
}

TEST_F(SimulateCli, BinaryFormatsHoldTheSameSamplesAsText) {
  const std::string model = "--rate 50 --duration 20 --N 1e-3 --R 1e-4 --channels 2 --seed 4 ";
  ASSERT_EQ(run(model + "-o " + path("s.txt")).status, 0);
  const CliResult r64 = run(model + "--format f64 -o " + path("s.f64"));
  ASSERT_EQ(r64.status, 0) << r64.err;
  EXPECT_NE(r64.err.find("wrote 1000 frames x 2 channels"), std::string::npos) << r64.err;
  ASSERT_EQ(run(model + "--format f32 -o " + path("s.f32")).status, 0);
  const std::string raw64 = slurp(path("s.f64"));
  const std::string raw32 = slurp(path("s.f32"));
  ASSERT_EQ(raw64.size(), 1000U * 2U * 8U);
  ASSERT_EQ(raw32.size(), 1000U * 2U * 4U);
  std::vector<double> text_values;
  for (const auto& line : lines(slurp(path("s.txt")))) {
    if (line.starts_with("#") || line.starts_with("ch")) continue;
    std::istringstream row(line);
    for (double v; row >> v;) text_values.push_back(v);
  }
  ASSERT_EQ(text_values.size(), 2000U);
  for (std::size_t i = 0; i < text_values.size(); ++i) {
    double v64;
    float v32;
    std::memcpy(&v64, raw64.data() + 8 * i, 8);  // test machines are little-endian
    std::memcpy(&v32, raw32.data() + 4 * i, 4);
    ASSERT_EQ(v64, text_values[i]) << i;  // text is the shortest round-trip representation
    ASSERT_EQ(v32, static_cast<float>(text_values[i])) << i;
  }
}

TEST_F(SimulateCli, StandardOutput) {
  const fs::path out = dir_ / "stdout.txt";
  const CliResult r = run("--rate 10 --duration 1 --N 1 -o - >\"" + out.string() + "\"");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto text = lines(slurp(out));
  ASSERT_GE(text.size(), 11U);
  EXPECT_EQ(text[text.size() - 11], "ch1");
}

TEST_F(SimulateCli, NeverOverwritesWithoutForce) {
  {
    std::ofstream(path("keep.txt")) << "precious\n";
  }
  const CliResult r = run("--rate 10 --duration 1 --N 1 -o " + path("keep.txt"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("file exists"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("keep.txt")), "precious\n");
  EXPECT_EQ(run("--rate 10 --duration 1 --N 1 --force -o " + path("keep.txt")).status, 0);
  EXPECT_NE(slurp(path("keep.txt")), "precious\n");
}

TEST_F(SimulateCli, BadInputExitsOneWithAClearMessageAndNoFile) {
  struct Case {
    const char* args;
    const char* message;
  };
  const Case cases[] = {
      {"--rate 100 --N -1", "N = -1 is negative"},
      {"--rate 100 --B nan", "B = nan is not a finite number"},
      {"--rate 100 --duration 0 --N 1", "duration = 0 s must be positive"},
      {"--rate 10 --sine-amp 1 --sine-freq 6", "below twice the sinusoid frequency"},
      {"--rate 100 --B 1 --flicker-tau-min 0.001", "below the sample interval"},
      {"--rate 100 --B 1 --flicker-tau-min 0.01 --flicker-tau-max 1e13", "decades"},
      {"--preset tg100 --N 1", "cannot be combined with --preset"},
      {"--preset nope", "unknown preset"},
      {"--N 1", "--rate HZ is required"},
      {"--rate 100 --format csv", "--format csv is not known"},
      {"--rate 100 --gm-sigma 1", "correlation time"},
  };
  for (const auto& c : cases) {
    const CliResult r = run(std::string(c.args) + " -o " + path("never.txt"));
    EXPECT_EQ(r.status, 1) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << " -> " << r.err;
    EXPECT_FALSE(fs::exists(path("never.txt"))) << c.args;
  }
}
