// imunoise dev with the total, Theo1 and time-error estimators: --estimator all, Theo1's tau
// convention, angle units of MTIE / TIE rms / ttotdev, and labelled bias-corrected curves.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

#include "cli/cli_runner.hpp"
#include "core/nbs14.hpp"

namespace imunoise {
namespace {

using test::run_cli;
using test::TempDir;

std::string nbs14_text() {
  std::string s;
  char buf[64];
  for (double v : test::nbs14_1000_point_frequency()) {
    std::snprintf(buf, sizeof buf, "%.17g\n", v);
    s += buf;
  }
  return s;
}

TEST(CliDevTotal, AllEstimatorsThroughJson) {
  TempDir dir;
  const auto file = dir.write("nbs14.txt", nbs14_text());
  const auto r = run_cli({"dev", file, "--rate", "1", "--units", "deg/s", "--estimator", "all",
                          "--taus", "octave", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 14u);
  bool saw_theo = false;
  for (const auto& curve : j) {
    const std::string name = curve["estimator"];
    const std::string unit = curve["unit"];
    if (name == "theo1") {
      saw_theo = true;
      EXPECT_EQ(curve["points"][0]["m"], 2);
      EXPECT_DOUBLE_EQ(curve["points"][0]["tau_s"].get<double>(), 1.5);
    }
    if (name == "mtie" || name == "tierms" || name == "ttotdev") {
      EXPECT_EQ(unit, "deg") << name;
      EXPECT_TRUE(curve["points"][0]["ci_low"].is_null() == (name != "ttotdev")) << name;
    }
    if (name == "mtotdev") {
      EXPECT_NEAR(curve["points"][1]["dev"].get<double>(), 1.4337e-01, 0.00005e-01);
      EXPECT_EQ(curve["points"][1]["edf_method"], "sp1065");
    }
  }
  EXPECT_TRUE(saw_theo);
}

TEST(CliDevTotal, TheoTausAndBiasCorrectedCurve) {
  TempDir dir;
  const auto file = dir.write("nbs14.txt", nbs14_text());
  const auto r = run_cli({"dev", file, "--rate", "1", "--estimator", "theo1", "--taus", "2,7.5",
                          "--format", "json"});
  // 2 s is not a Theo1 tau (0.75 m for even m): refused, naming the rule.
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("0.75 m"), std::string::npos) << r.err;
  const auto theo = run_cli({"dev", file, "--rate", "1", "--estimator", "theo1", "--taus",
                             "1.5,7.5", "--format", "json"});
  ASSERT_EQ(theo.exit_code, 0) << theo.err;
  const auto t = nlohmann::json::parse(theo.out);
  EXPECT_EQ(t["points"][1]["m"], 10);
  EXPECT_NEAR(t["points"][1]["dev"].get<double>(), 1.0757e-01, 0.00005e-01);  // Stable32
  const auto ok = run_cli({"dev", file, "--rate", "1", "--estimator", "htotdev", "--af", "2",
                           "--format", "json", "--bias-correct", "--noise-type", "0"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const auto j = nlohmann::json::parse(ok.out);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0]["estimator"], "htotdev");
  EXPECT_EQ(j[1]["estimator"], "htotdev-bc");
  EXPECT_EQ(j[1]["bias_corrected"], true);
  EXPECT_NEAR(j[0]["points"][0]["dev"].get<double>(), 2.0247e-01, 0.00005e-01);  // Stable32, raw
  EXPECT_NEAR(j[1]["points"][0]["dev"].get<double>(), 2.0297e-01, 0.00005e-01);  // corrected
}

}  // namespace
}  // namespace imunoise

namespace imunoise {
namespace {

// mtotdev on 1000 points at octave taus: m = 1..256, the estimate (N - 3m + 1) 6m ns sums to
// ~0.5 ms; a 0.1 ms budget keeps the short taus and skips the long ones with a note, in the
// JSON and on standard error, and the run still succeeds.
TEST(CliDevTotal, TheoBrReproducesStable32AndStatesItsFactor) {
  test::TempDir dir;
  const auto file = dir.write("nbs14.txt", nbs14_text());
  const auto r = test::run_cli({"dev", file, "--rate", "1", "--estimator", "theobr", "--af", "10",
                                "--theobr-ratios", "stable32", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["points"][0]["dev"].get<double>(), 8.3520e-02, 0.00005e-02);
  EXPECT_EQ(j["theobr_bias_factor"]["ratios"], 164);
  EXPECT_NE(j["note"].get<std::string>().find("stable32 rule"), std::string::npos);
  const auto bad = test::run_cli({"dev", file, "--rate", "1", "--estimator", "theobr",
                                  "--theobr-ratios", "nist"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("taylor-howe"), std::string::npos) << bad.err;
}

TEST(CliDevTotal, TheoBrOverBudgetIsSkippedWholeWithANote) {
  test::TempDir dir;
  const auto file = dir.write("nbs14.txt", nbs14_text());
  const auto r = test::run_cli({"dev", file, "--rate", "1", "--estimator", "oadev,theobr",
                                "--format", "json", "--no-ci", "--time-budget", "1e-6"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_FALSE(j[0]["points"].empty());
  EXPECT_TRUE(j[1]["points"].empty());
  EXPECT_FALSE(j[1]["skipped_factors"].empty());
  EXPECT_NE(j[1]["note"].get<std::string>().find("bias factor"), std::string::npos);
  EXPECT_NE(r.err.find("theobr skipped"), std::string::npos) << r.err;
}

// Absent numbers (no EDF for mtie, no bounds with --no-ci) are "-" in the table and empty in
// CSV, never "nan"; the table says when there are no bounds.
TEST(CliDevTotal, AbsentNumbersAreNeverNan) {
  test::TempDir dir;
  const auto file = dir.write("nbs14.txt", nbs14_text());
  for (const char* format : {"table", "csv"}) {
    for (const bool no_ci : {false, true}) {
      std::vector<std::string> args{"dev", file, "--rate", "1", "--estimator", "oadev,mtie",
                                    "--af", "1,10", "--format", format};
      if (no_ci) args.push_back("--no-ci");
      const auto r = test::run_cli(args);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(r.out.find("nan"), std::string::npos) << format << " no_ci=" << no_ci << "\n" << r.out;
      if (no_ci && std::string(format) == "table") {
        EXPECT_NE(r.out.find("no confidence bounds (--no-ci)"), std::string::npos) << r.out;
      }
    }
  }
}

TEST(CliDevTotal, TimeBudgetSkipsTheLongestTausWithANote) {
  test::TempDir dir;
  const auto file = dir.write("nbs14.txt", nbs14_text());
  const auto full = test::run_cli({"dev", file, "--rate", "1", "--estimator", "mtotdev",
                                   "--format", "json", "--no-ci"});
  ASSERT_EQ(full.exit_code, 0) << full.err;
  const auto all = nlohmann::json::parse(full.out);
  EXPECT_FALSE(all.contains("skipped_factors"));
  const auto r = test::run_cli({"dev", file, "--rate", "1", "--estimator", "mtotdev", "--format",
                                "json", "--no-ci", "--time-budget", "0.0001"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("skipped_factors"));
  const auto kept = j["points"].size();
  const auto skipped = j["skipped_factors"].size();
  EXPECT_GT(kept, 0u);
  EXPECT_GT(skipped, 0u);
  EXPECT_EQ(kept + skipped, all["points"].size());
  // The kept points are the short taus, unchanged.
  for (std::size_t i = 0; i < kept; ++i) {
    EXPECT_EQ(j["points"][i]["dev"], all["points"][i]["dev"]);
  }
  EXPECT_EQ(j["skipped_factors"][0], all["points"][kept]["m"]);
  EXPECT_NE(r.err.find("--time-budget"), std::string::npos) << r.err;
  EXPECT_NE(j["note"].get<std::string>().find("skipped"), std::string::npos);
}

}  // namespace
}  // namespace imunoise
