// imunoise analyze / demo as a user runs them: the report directory, bad inputs among good
// ones (--keep-going), inputs that cannot be studied together, and a DIR that cannot be used.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace imunoise::test {
namespace {

// A white-noise gyro record in deg/s: `n` rows "t,gx,gy" at `rate` Hz.
std::string csv_record(std::size_t n, double rate, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 0.01);
  std::string text = "t,gx,gy\n";
  for (std::size_t i = 0; i < n; ++i) {
    text += std::to_string(static_cast<double>(i) / rate) + "," + std::to_string(normal(rng)) +
            "," + std::to_string(normal(rng)) + "\n";
  }
  return text;
}

TEST(CliAnalyze, WritesTheReportOfEveryColumn) {
  TempDir dir;
  const auto file = dir.write("imu.csv", csv_record(20000, 100.0, 1));
  const auto out = dir.file("report");
  const auto r = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "--spec",
                          "tg100", "-o", out, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("report: " + out + "/report.html"), std::string::npos) << r.out;
  const auto doc = nlohmann::json::parse(slurp(out + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 2u);
  EXPECT_EQ(doc["channels"][0]["name"], "gx");
  EXPECT_EQ(doc["channels"][1]["name"], "gy");
  EXPECT_EQ(doc["channels"][0]["unit"], "deg/s");
  EXPECT_FALSE(doc["channels"][0]["fit"].is_null());
  // The same record through `fit` gives the same fit document.
  const auto fit = run_cli({"fit", file, "--time-column", "t", "--column", "gx", "--units", "deg/s"});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto fit_doc = nlohmann::json::parse(fit.out);
  EXPECT_EQ(doc["channels"][0]["fit"]["terms"], fit_doc["terms"]);
  // Nothing on stderr with --quiet and a clean record but possible fit warnings: no progress.
  EXPECT_EQ(r.err.find("%]"), std::string::npos) << r.err;
  // An existing report is not replaced without --force.
  const auto again = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "-o", out});
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  const auto forced = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "-o",
                               out, "--force", "--quiet"});
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
}

// The fit options are the fit command's: analyze --method gmwm --robust fits every channel by
// the robust GMWM, and the channel's fit document is the one `fit` writes for that column.
TEST(CliAnalyze, RobustGmwmReachesEveryChannelAsInFit) {
  TempDir dir;
  const auto file = dir.write("imu.csv", csv_record(20000, 100.0, 4));
  const auto out = dir.file("report");
  const auto r = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "--method", "gmwm",
                          "--terms", "N", "--robust", "-o", out, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 2u);
  for (const auto& channel : doc["channels"]) {
    EXPECT_EQ(channel["fit"]["method"], "gmwm");
    EXPECT_TRUE(channel["fit"]["gmwm"]["robust"].get<bool>()) << channel["name"];
  }
  const auto fit = run_cli({"fit", file, "--time-column", "t", "--column", "gy", "--units", "deg/s", "--method",
                            "gmwm", "--terms", "N", "--robust"});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(doc["channels"][1]["fit"]["terms"], nlohmann::json::parse(fit.out)["terms"]);
  // Without --method gmwm the flag is refused before any work: no report directory.
  const auto bad = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "--robust", "-o",
                            dir.file("none"), "--quiet"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--robust needs --method gmwm"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("none")));
}

// The terminal gets one line a channel (what was fitted, how many diagnostics); --verbose adds
// every diagnostic, which the report holds in any case.
TEST(CliAnalyze, OneLineAChannelAndEveryDiagnosticWithVerbose) {
  TempDir dir;
  // Values on a 0.01 deg/s grid: few distinct values, so the record checks have something to say.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 0.01);
  std::string text = "t,gx,gy\n";
  for (int i = 0; i < 20000; ++i) {
    text += std::to_string(i / 100.0) + "," + std::to_string(std::round(normal(rng) * 100.0) / 100.0) + "," +
            std::to_string(std::round(normal(rng) * 100.0) / 100.0) + "\n";
  }
  const auto file = dir.write("imu.csv", text);
  const auto r = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "-o", dir.file("a"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"gx", "gy"}) {
    EXPECT_NE(r.err.find(std::string("imunoise: ") + name + ": fitted N"), std::string::npos) << r.err;
  }
  EXPECT_EQ(r.err.find("imunoise: warning:"), std::string::npos) << r.err;
  const auto doc = nlohmann::json::parse(slurp(dir.file("a") + "/report.json"));
  std::size_t diagnostics = 0;
  for (const auto& ch : doc["channels"]) diagnostics += ch["warnings"].size();
  const auto v = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "-o", dir.file("b"), "-q",
                          "--verbose"});
  ASSERT_EQ(v.exit_code, 0) << v.err;
  ASSERT_GT(diagnostics, 0u) << "the quantized record gave no diagnostic to print";
  EXPECT_NE(r.err.find("diagnostic"), std::string::npos) << r.err;
  std::size_t printed = 0;
  for (std::size_t at = 0; (at = v.err.find("imunoise: warning:", at)) != std::string::npos; ++at) ++printed;
  EXPECT_EQ(printed, diagnostics) << v.err;
}

// An existing report is refused before any input is read or studied: with a broken input the
// refusal, not the input's error, is what the user sees (no minutes of work thrown away).
TEST(CliAnalyze, ExistingReportIsRefusedBeforeTheWork) {
  TempDir dir;
  const auto broken = dir.write("broken.csv", "t,gx\n0,1\n0.01,not-a-number\n");
  const auto out = dir.file("report");
  std::filesystem::create_directories(out);
  dir.write("report/report.json", "{}\n");
  const auto r = run_cli({"analyze", broken, "--time-column", "t", "--units", "deg/s", "-o", out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("already holds report.json"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(out + "/report.json"), "{}\n");
}

TEST(CliAnalyze, BrokenFileAmongGoodOnesIsNamedAndKeepGoingFinishesTheOthers) {
  TempDir dir;
  const auto good1 = dir.write("a.csv", csv_record(8000, 100.0, 2));
  const auto good2 = dir.write("b.csv", csv_record(8000, 100.0, 3));
  const auto bad = dir.write("broken.csv", "t,gx,gy\n0,1,2\n0.01,x,3\n");
  const auto out = dir.file("report");
  const std::vector<std::string> common{"--time-column", "t", "--columns", "gx", "--units",
                                        "deg/s", "-o", out, "--quiet"};
  auto args = std::vector<std::string>{"analyze", good1, bad, good2};
  args.insert(args.end(), common.begin(), common.end());
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--keep-going"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/report.json"));
  args.push_back("--keep-going");
  const auto k = run_cli(args);
  ASSERT_EQ(k.exit_code, 0) << k.err;
  EXPECT_NE(k.err.find("broken.csv"), std::string::npos) << k.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 2u);
  bool named = false;
  for (const auto& in : doc["inputs"]) {
    named = named || (in["status"] == "unreadable" &&
                      in["source"].get<std::string>().find("broken.csv") != std::string::npos);
  }
  EXPECT_TRUE(named);
}

TEST(CliAnalyze, MismatchedRatesAndUnitsAreRefused) {
  TempDir dir;
  const auto a = dir.write("a.csv", csv_record(5000, 100.0, 4));
  const auto b = dir.write("b.csv", csv_record(5000, 200.0, 5));
  const auto rates = run_cli({"analyze", a, b, "--time-column", "t", "--columns", "gx", "--units",
                              "deg/s", "-o", dir.file("r1"), "--quiet"});
  EXPECT_EQ(rates.exit_code, 1);
  EXPECT_NE(rates.err.find("200 Hz"), std::string::npos) << rates.err;
  const auto units = run_cli({"analyze", a, "--time-column", "t", "--units", "deg/s,rad/s", "-o",
                              dir.file("r2"), "--quiet"});
  EXPECT_EQ(units.exit_code, 1);
  EXPECT_NE(units.err.find("rad/s"), std::string::npos) << units.err;
  const auto count = run_cli({"analyze", a, "--time-column", "t", "--units", "deg/s,deg/s,deg/s",
                              "-o", dir.file("r3"), "--quiet"});
  EXPECT_EQ(count.exit_code, 1);
  EXPECT_NE(count.err.find("3 units for 2 channels"), std::string::npos) << count.err;
}

TEST(CliAnalyze, UnusableDirectoryIsAnError) {
  TempDir dir;
  const auto a = dir.write("a.csv", csv_record(5000, 100.0, 6));
  const auto file = dir.write("not-a-dir", "x");
  const auto r = run_cli({"analyze", a, "--time-column", "t", "--units", "deg/s", "-o", file, "--quiet"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a directory"), std::string::npos) << r.err;
  const auto r2 = run_cli({"analyze", a, "--time-column", "t", "--units", "deg/s", "-o",
                           file + "/sub", "--quiet"});
  EXPECT_EQ(r2.exit_code, 1);
  EXPECT_NE(r2.err.find("cannot create"), std::string::npos) << r2.err;
}

}  // namespace
}  // namespace imunoise::test

namespace imunoise::test {
namespace {

// The demo on a short record (the 6-hour run is SlowDemo in tests/study): the summary on
// stdout, the report in DIR, no progress when stderr is not a terminal, no overwrite.
TEST(CliDemo, PrintsTheSummaryAndWritesTheReport) {
  TempDir dir;
  const auto out = dir.file("demo");
  const auto r = run_cli({"demo", "--hours", "0.25", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"Table 2", "gyro1  N", "Datasheet comparison", "Navigation error after 1 h",
                           "why they differ", "report: "}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  }
  EXPECT_EQ(r.err.find("%]"), std::string::npos) << "progress on a non-terminal stderr: " << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(doc["channels"].size(), 4u);
  EXPECT_FALSE(doc["redundant"].is_null());
  EXPECT_EQ(doc["reference"]["rows"].size(), 16u);
  const auto again = run_cli({"demo", "--hours", "0.25", "-o", out});
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
}

}  // namespace
}  // namespace imunoise::test

namespace imunoise::test {
namespace {

// analyze --davar: each channel's dynamic Allan variance in report.json, its heat map as a
// figure file and its verdict in report.md. gy's noise triples at 60 s of 200 s: not
// stationary, the first change found within half a window (10 s) of 60 s and every window
// before it flagged; gx is white throughout.
TEST(CliAnalyze, DavarHeatMapAndVerdictInTheReport) {
  TempDir dir;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 0.01);
  std::string text = "t,gx,gy\n";
  for (std::size_t i = 0; i < 20000; ++i) {
    const double t = static_cast<double>(i) / 100.0;
    text += std::to_string(t) + "," + std::to_string(normal(rng)) + "," +
            std::to_string(normal(rng) * (t >= 60.0 ? 3.0 : 1.0)) + "\n";
  }
  const auto file = dir.write("imu.csv", text);
  const auto out = dir.file("report");
  const auto r = run_cli({"analyze", file, "--time-column", "t", "--units", "deg/s", "--davar",
                          "--davar-window", "20", "-o", out, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/report.json"));
  const auto& gx = doc["channels"][0]["davar"];
  const auto& gy = doc["channels"][1]["davar"];
  ASSERT_TRUE(gx.is_object() && gy.is_object());
  EXPECT_EQ(gx["window_s"], 20.0);
  EXPECT_TRUE(gx["stationary"].get<bool>());
  EXPECT_FALSE(gy["stationary"].get<bool>());
  // The first change is the step; every window wholly before it is flagged.
  ASSERT_GE(gy["change_times_s"].size(), 1u);
  EXPECT_NEAR(gy["change_times_s"][0].get<double>(), 60.0, 10.0);
  for (std::size_t w = 0; w < gy["window_start_s"].size(); ++w) {
    if (gy["window_start_s"][w].get<double>() + 20.0 <= 60.0) {
      EXPECT_TRUE(gy["window_flagged"][w].get<bool>()) << w;
    }
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/figures/davar_gy.svg"));
  EXPECT_TRUE(std::filesystem::exists(out + "/figures/davar_gx.png"));
  const auto md = slurp(out + "/report.md");
  EXPECT_NE(md.find("- gy: "), std::string::npos) << md;
  EXPECT_NE(md.find("NOT stationary"), std::string::npos);
  EXPECT_NE(md.find("changes near t = "), std::string::npos);
}

}  // namespace
}  // namespace imunoise::test
