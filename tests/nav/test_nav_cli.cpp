// `imunoise nav` as a user runs it: contract fields, --from FIT.json, and every bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"

namespace imunoise::test {
namespace {

std::string fit_document(double n, double b, double k, const std::string& unit = "deg/s") {
  auto term = [](double v) {
    return nlohmann::json{{"value", v}, {"unit", "x"}, {"identified", v > 0}};
  };
  nlohmann::json doc{{"unit", unit},
                     {"method", "wls"},
                     {"terms", {{"Q", term(0)}, {"N", term(n)}, {"B", term(b)}, {"K", term(k)}, {"R", term(0)}}}};
  return doc.dump();
}

void expect_error(const std::vector<std::string>& args, const std::string& needle) {
  const CliResult r = run_cli(args);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
  EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
}

TEST(NavCli, JsonContractAndThePapersLongitude) {
  const CliResult r = run_cli({"nav", "--N", "8.9e-4", "--model", "paper,schuler,covariance", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(doc["latitude_deg"].get<double>(), 58.5);
  ASSERT_EQ(doc["models"].size(), 3U);
  for (const auto& m : doc["models"]) {
    for (const char* key : {"t_s", "lat_deg", "lon_deg", "path_m", "radial_m"}) {
      ASSERT_TRUE(m.contains(key)) << key;
      EXPECT_EQ(m[key].size(), m["t_s"].size());
    }
    EXPECT_DOUBLE_EQ(m["t_s"][1].get<double>(), 60.0);
  }
  EXPECT_EQ(doc["models"][0]["model"], "paper");
  EXPECT_NEAR(doc["models"][0]["lon_deg"].back().get<double>(), 3.9, 0.05);
  // The sigma_eps each published figure needs: only the longitude's is gyro 1's N.
  const auto& need = doc["models"][0]["sigma_eps_for_published_deg_s"];
  EXPECT_NEAR(need["lon"].get<double>() / 8.9e-4, 1.0, 0.005);
  EXPECT_NEAR(need["lat"].get<double>(), 3.6827e-4, 1e-8);
  EXPECT_NEAR(need["path"].get<double>(), 4.6320e-5, 1e-9);
  // ARW only: the Schuler path error at 1 h is references.md's 8.33 km.
  EXPECT_NEAR(doc["models"][1]["path_m"].back().get<double>() / 8.33e3, 1.0, 0.005);
}

TEST(NavCli, TableShowsModelsSideBySideWithThePublishedFigures) {
  const CliResult r = run_cli({"nav", "--N", "8.9e-4", "--B", "5.9e-4", "--K", "1.5e-5", "--model", "paper,schuler"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("paper (published)"), std::string::npos);
  EXPECT_NE(r.out.find("22.6"), std::string::npos);
  EXPECT_NE(r.out.find("path [km]"), std::string::npos);
  EXPECT_NE(r.out.find("absent terms"), std::string::npos);
}

TEST(NavCli, FromFitJsonPerAxisAndForAll) {
  TempDir dir;
  const std::string x = dir.write("x.json", fit_document(8.6e-4, 5.3e-4, 1.2e-5));
  const std::string y = dir.write("y.json", fit_document(8.9e-4, 5.9e-4, 1.5e-5));
  const std::string z = dir.write("z.json", fit_document(8.8e-4, 5.3e-4, 1.1e-5));
  CliResult r = run_cli({"nav", "--from-x", x, "--from-y", y, "--from-z", z, "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto doc = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(doc["axes"][0]["N_deg_sqrt_s"].get<double>(), 8.6e-4);
  EXPECT_DOUBLE_EQ(doc["axes"][1]["N_deg_sqrt_s"].get<double>(), 8.9e-4);
  EXPECT_DOUBLE_EQ(doc["axes"][2]["K_deg_s_sqrt_s"].get<double>(), 1.1e-5);
  r = run_cli({"nav", "--from", y, "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  doc = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(doc["axes"][0]["B_deg_s"].get<double>(), 5.9e-4);
}

// terms.GM is a list by correlation time (every GM term of a gmwm fit): each one reaches the
// navigation error; the single object of older fit documents is still read.
TEST(NavCli, FromAFitDocumentWithSeveralGaussMarkovTerms) {
  auto gm = [](double sigma, double tc) {
    return nlohmann::json{{"sigma", {{"value", sigma}, {"unit", "deg/s"}, {"identified", true}}},
                          {"correlation_time_s", {{"value", tc}, {"unit", "s"}, {"identified", true}}}};
  };
  auto with = [&](const nlohmann::json& list) {
    auto doc = nlohmann::json::parse(fit_document(8.9e-4, 0.0, 0.0));
    doc["terms"]["GM"] = list;
    return doc.dump();
  };
  TempDir dir;
  const std::string both = dir.write("both.json", with(nlohmann::json::array({gm(2e-3, 600.0), gm(1e-3, 30.0)})));
  const std::string first = dir.write("first.json", with(nlohmann::json::array({gm(1e-3, 30.0)})));
  const std::string old = dir.write("old.json", with(gm(1e-3, 30.0)));
  auto radial = [](const nlohmann::json& doc) { return doc["models"][0]["radial_m"].back().get<double>(); };
  const CliResult rb = run_cli({"nav", "--from", both, "--model", "covariance", "--format", "json"});
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  const auto db = nlohmann::json::parse(rb.out);
  const auto& listed = db["axes"][1]["gauss_markov"];
  ASSERT_EQ(listed.size(), 2u) << db["axes"][1];
  EXPECT_DOUBLE_EQ(listed[0]["time_s"].get<double>(), 30.0);  // sorted by correlation time
  EXPECT_DOUBLE_EQ(listed[1]["sigma_deg_s"].get<double>(), 2e-3);
  const CliResult rf = run_cli({"nav", "--from", first, "--model", "covariance", "--format", "json"});
  ASSERT_EQ(rf.exit_code, 0) << rf.err;
  const auto df = nlohmann::json::parse(rf.out);
  EXPECT_GT(radial(db), 1.2 * radial(df));
  const CliResult ro = run_cli({"nav", "--from", old, "--model", "covariance", "--format", "json"});
  ASSERT_EQ(ro.exit_code, 0) << ro.err;
  EXPECT_DOUBLE_EQ(radial(nlohmann::json::parse(ro.out)), radial(df));
  expect_error({"nav", "--from", dir.write("bad.json", with(nlohmann::json("GM"))), "--format", "json"}, "terms.GM");
}

TEST(NavCli, FromTheOutputOfFit) {
  TempDir dir;
  const std::string rec = dir.file("gyro.txt");
  ASSERT_EQ(run_cli({"simulate", "--rate", "50", "--duration", "2000", "--N", "8.9e-4", "--seed", "3", "-o", rec}).exit_code, 0);
  const std::string fit = dir.file("fit.json");
  const CliResult f = run_cli({"fit", rec, "--rate", "50", "--units", "deg/s", "--format", "json", "-o", fit});
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const auto fit_doc = nlohmann::json::parse(slurp(fit));
  const CliResult r = run_cli({"nav", "--from", fit, "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_NEAR(doc["axes"][1]["N_deg_sqrt_s"].get<double>(), fit_doc["terms"]["N"]["value"].get<double>(), 1e-15);
}

TEST(NavCli, BadInputEndsWithExitOneAndAClearMessage) {
  expect_error({"nav", "--N", "1e-3", "--hours", "0"}, "--hours must be positive");
  expect_error({"nav", "--N", "1e-3", "--hours", "-2"}, "--hours must be positive");
  expect_error({"nav", "--N", "1e-3", "--latitude", "91"}, "beyond +-90");
  expect_error({"nav", "--N", "1e-3", "--latitude", "-95"}, "beyond +-90");
  expect_error({"nav", "--N", "1e-3", "--units", "m/s^2"}, "not an angular rate");
  expect_error({"nav", "--N", "1e-3", "--units", "deg"}, "not an angular rate");
  expect_error({"nav", "--N", "-1e-3"}, "--N must be >= 0");
  expect_error({"nav", "--hours", "1"}, "no noise term");
  expect_error({"nav", "--N", "1e-3", "--model", "kalman"}, "unknown model 'kalman'");
  expect_error({"nav", "--N", "1e-3", "--format", "xml"}, "unknown --format");
  expect_error({"nav", "--N", "1e-3", "--step", "0.5"}, "--step");
  expect_error({"nav", "--N", "1e-3", "--model", "montecarlo", "--runs", "1"}, "at least 2 runs");
  expect_error({"nav", "--B", "1e-3", "--model", "paper"}, "--sigma-eps");
  expect_error({"nav", "--gm-sigma", "1e-3"}, "--gm-tau");
  TempDir dir;
  const std::string fit = dir.write("fit.json", fit_document(8.9e-4, 0, 0));
  expect_error({"nav", "--from", fit, "--N", "1e-3"}, "not both");
  expect_error({"nav", "--from-x", fit}, "all three");
  expect_error({"nav", "--from", dir.file("missing.json")}, "missing.json: cannot open");
  expect_error({"nav", "--from", dir.write("text.json", "tau adev\n1 2\n")}, "text.json: not JSON");
  expect_error({"nav", "--from", dir.write("array.json", "[1, 2]")}, "array.json: not an imunoise fit document");
  nlohmann::json no_k = nlohmann::json::parse(fit_document(1e-3, 0, 0));
  no_k["terms"].erase("K");
  expect_error({"nav", "--from", dir.write("nok.json", no_k.dump())}, "nok.json: not an imunoise fit document: missing field 'terms.K'");
  expect_error({"nav", "--from", dir.write("accel.json", fit_document(1e-3, 0, 0, "m/s^2"))}, "accel.json: the fit's unit 'm/s^2' is not an angular rate");
  expect_error({"nav", "--from", dir.write("nounit.json", fit_document(1e-3, 0, 0, "input unit"))}, "without --units");
  const std::string out = dir.write("out.txt", "keep me");
  expect_error({"nav", "--N", "1e-3", "-o", out}, "file exists");
  EXPECT_EQ(slurp(out), "keep me");
}

TEST(NavCli, AtThePoleLongitudeIsNullAndPathIsReported) {
  const CliResult r = run_cli({"nav", "--N", "8.9e-4", "--latitude", "90", "--format", "json", "--hours", "0.5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("longitude is undefined at the pole"), std::string::npos);
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_FALSE(doc["longitude_defined"].get<bool>());
  for (const auto& m : doc["models"]) {
    EXPECT_TRUE(m["lon_deg"].is_null());
    EXPECT_GT(m["path_m"].back().get<double>(), 0.0);
  }
}

TEST(NavCli, AbsentTermsAreNamedOnStandardError) {
  TempDir dir;
  const std::string fit = dir.write("fit.json", fit_document(8.9e-4, 0, 0));
  const CliResult r = run_cli({"nav", "--from", fit, "--format", "csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("B (all axes)"), std::string::npos);
  EXPECT_NE(r.err.find("K (all axes)"), std::string::npos);
  EXPECT_NE(r.out.find("t_s,schuler_lat_deg"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::test
