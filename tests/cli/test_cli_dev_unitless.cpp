// imunoise dev on unitless input (no --units): clock phase in seconds and fractional frequency,
// the standard case for time-and-frequency data. Every estimator must run on both and label its
// result with the input unit: the rate-unit estimators in "input unit/s" for phase input
// ("input unit" for frequency input), the angle-unit ones (tdev, ttotdev, mtie, tierms) in
// "input unit" for phase input ("input unit*s" for frequency input).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "core/nbs14.hpp"

namespace imunoise {
namespace {

using test::column_text;
using test::run_cli;
using test::TempDir;

bool reports_angle_unit(const std::string& estimator) {
  return estimator == "tdev" || estimator == "ttotdev" || estimator == "mtie" || estimator == "tierms";
}

const std::vector<std::string> kEstimators = {"adev",    "oadev",   "mdev",    "tdev",  "hdev",
                                              "ohdev",   "totdev",  "mtotdev", "ttotdev",
                                              "htotdev", "theo1",   "theobr",  "mtie",  "tierms"};

nlohmann::json run_json(const std::vector<std::string>& args) {
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return {};
  return nlohmann::json::parse(r.out);
}

class CliDevUnitless : public ::testing::TestWithParam<std::string> {};

// Unitless phase (seconds): runs, labelled with the input unit, with and without intervals.
TEST_P(CliDevUnitless, PhaseInput) {
  const std::string estimator = GetParam();
  TempDir dir;
  const auto file = dir.write("phase.txt", column_text(test::nbs14_phase_dat()));
  for (const char* phase_name : {"phase", "angle"}) {
    for (const bool ci : {true, false}) {
      std::vector<std::string> args = {"dev", file, "--rate", "1", "--input", phase_name,
                                       "--estimator", estimator, "--format", "json"};
      if (!ci) args.push_back("--no-ci");
      const auto j = run_json(args);
      if (j.is_null()) continue;
      EXPECT_EQ(j["unit"], reports_angle_unit(estimator) ? "input unit" : "input unit/s");
      ASSERT_FALSE(j["points"].empty());
      for (const auto& p : j["points"]) EXPECT_TRUE(std::isfinite(p["dev"].get<double>()));
    }
  }
  // The table says the unit too.
  const auto r = run_cli({"dev", file, "--rate", "1", "--input", "phase", "--estimator", estimator});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string label =
      estimator + " [" + (reports_angle_unit(estimator) ? "input unit" : "input unit/s") + "]";
  EXPECT_NE(r.out.find(label), std::string::npos) << r.out;
}

// Unitless fractional frequency: runs, labelled "input unit" (rate) or "input unit*s" (angle).
TEST_P(CliDevUnitless, FrequencyInput) {
  const std::string estimator = GetParam();
  TempDir dir;
  const auto file = dir.write("freq.txt", column_text(test::nbs14_1000_point_frequency()));
  const auto j = run_json({"dev", file, "--rate", "1", "--input", "freq", "--estimator", estimator,
                           "--format", "json"});
  if (j.is_null()) return;
  EXPECT_EQ(j["unit"], reports_angle_unit(estimator) ? "input unit*s" : "input unit");
  ASSERT_FALSE(j["points"].empty());
}

INSTANTIATE_TEST_SUITE_P(Every, CliDevUnitless, ::testing::ValuesIn(kEstimators),
                         [](const auto& param_info) { return param_info.param; });

// Values in the input unit: unitless phase gives the published NBS14 10-point tdev and mdev
// (SP 1065; references.md) and Stable32's PHASE.DAT MTIE and TIE rms rows, unscaled.
TEST(CliDevUnitlessValues, PublishedNumbersFromUnitlessPhase) {
  TempDir dir;
  const std::vector<double> ten = {0, 103.11111, 123.22222, 157.33333, 166.44444,
                                   48.55555, -96.33333, -2.22222, 111.88889, 0};
  const auto nbs10 = dir.write("nbs10.txt", column_text(ten));
  auto j = run_json({"dev", nbs10, "--rate", "1", "--input", "phase", "--estimator", "tdev,mdev",
                     "--af", "1,2", "--format", "json", "--no-ci"});
  ASSERT_TRUE(j.is_array());
  // The 10-point phase is printed to 5 decimals: ~1e-6 relative.
  EXPECT_NEAR(j[0]["points"][0]["dev"].get<double>() / 52.67135, 1.0, 2e-6);
  EXPECT_NEAR(j[0]["points"][1]["dev"].get<double>() / 86.35831, 1.0, 2e-6);
  EXPECT_NEAR(j[1]["points"][1]["dev"].get<double>() / 74.78849, 1.0, 2e-6);
  EXPECT_EQ(j[0]["unit"], "input unit");
  EXPECT_EQ(j[1]["unit"], "input unit/s");

  const auto phase = dir.write("phase.txt", column_text(test::nbs14_phase_dat()));
  j = run_json({"dev", phase, "--rate", "1", "--input", "phase", "--estimator", "mtie",
                "--af", "3", "--format", "json"});
  ASSERT_FALSE(j.is_null());
  EXPECT_NEAR(j["points"][0]["dev"].get<double>() / 1.2984, 1.0, 5e-5);  // Stable32, 5 digits
  EXPECT_EQ(j["points"][0]["n"], 998);
  j = run_json({"dev", phase, "--rate", "1", "--input", "phase", "--estimator", "tierms",
                "--af", "2", "--format", "json"});
  ASSERT_FALSE(j.is_null());
  EXPECT_NEAR(j["points"][0]["dev"].get<double>() / 0.40240, 1.0, 5e-5);
  EXPECT_EQ(j["points"][0]["n"], 999);
}

// Unitless phase and the same record declared in seconds (--units s) give the same numbers.
TEST(CliDevUnitlessValues, SameAsSecondsDeclared) {
  TempDir dir;
  const auto phase = dir.write("phase.txt", column_text(test::nbs14_phase_dat()));
  for (const char* estimator : {"tdev", "ttotdev", "mtie", "tierms", "oadev"}) {
    const auto bare = run_json({"dev", phase, "--rate", "1", "--input", "phase", "--estimator",
                                estimator, "--format", "json", "--no-ci"});
    const auto secs = run_json({"dev", phase, "--rate", "1", "--input", "phase", "--units", "s",
                                "--estimator", estimator, "--format", "json", "--no-ci"});
    ASSERT_FALSE(bare.is_null());
    ASSERT_FALSE(secs.is_null());
    ASSERT_EQ(bare["points"].size(), secs["points"].size()) << estimator;
    for (std::size_t i = 0; i < bare["points"].size(); ++i) {
      EXPECT_EQ(bare["points"][i]["dev"].get<double>(), secs["points"][i]["dev"].get<double>())
          << estimator;
    }
  }
}

}  // namespace
}  // namespace imunoise
