// imunoise fit as a user runs it: the interface.md JSON, the table, and bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace imunoise {
namespace {

using test::run_cli;
using test::TempDir;

TEST(CliFit, JsonFollowsTheInterfaceContract) {
  TempDir dir;
  const std::string file = dir.file("g.f64");
  const auto sim = run_cli({"simulate", "--rate", "200", "--duration", "1800", "--N", "8.9e-4",
                            "--B", "5.9e-4", "--units", "deg/s", "--seed", "3", "--format", "f64",
                            "-o", file});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto r = run_cli({"fit", file, "--binary", "f64", "--rate", "200", "--units", "deg/s",
                          "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["unit"], "deg/s");
  EXPECT_EQ(j["method"], "wls");
  const auto& n = j["terms"]["N"];
  EXPECT_EQ(n["unit"], "deg/sqrt(s)");
  EXPECT_TRUE(n["identified"].get<bool>());
  EXPECT_NEAR(n["value"].get<double>(), 8.9e-4, 8.9e-4 * 0.01);
  EXPECT_LE(n["ci_low"].get<double>(), n["value"].get<double>());
  EXPECT_GE(n["ci_high"].get<double>(), n["value"].get<double>());
  EXPECT_EQ(n["customary"]["unit"], "deg/sqrt(h)");
  EXPECT_NEAR(n["customary"]["value"].get<double>(), n["value"].get<double>() * 60, 1e-9);
  EXPECT_EQ(j["terms"]["B"]["customary"]["unit"], "deg/h");
  EXPECT_NEAR(j["terms"]["B"]["customary"]["value"].get<double>(),
              j["terms"]["B"]["value"].get<double>() * 3600, 1e-9);
  for (const char* absent : {"Q", "R"}) {
    EXPECT_FALSE(j["terms"][absent]["identified"].get<bool>()) << absent;
    EXPECT_EQ(j["terms"][absent]["value"].get<double>(), 0.0) << absent;
  }
  EXPECT_EQ(j["terms"]["K"]["customary"]["unit"], "deg/h/sqrt(h)");
  EXPECT_TRUE(j["diagnostics"]["residuals"].is_array());
  EXPECT_TRUE(j["paper"].contains("tau_opt_s"));
  EXPECT_EQ(r.out.find("NaN"), std::string::npos);

  for (const char* method : {"ols", "slope"}) {
    const auto m = run_cli({"fit", file, "--binary", "f64", "--rate", "200", "--units", "deg/s",
                            "--method", method, "--format", "table"});
    EXPECT_EQ(m.exit_code, 0) << m.err;
    EXPECT_NE(m.out.find("deg/sqrt(h)"), std::string::npos) << method;
    EXPECT_EQ(m.out.find(" nan"), std::string::npos) << method;
    EXPECT_EQ(m.out.find(" -nan"), std::string::npos) << method;
  }
}

TEST(CliFit, OptionalGaussMarkovAndSinusoidTerms) {
  // 30 min at 200 Hz with a Gauss-Markov term (1.5e-3 deg/s, 2 s): sigma scatters ~6% run to
  // run at this length (the 1 h Monte-Carlo study scatters 4.3%), so 25% is a 4-sigma bound.
  TempDir dir;
  const std::string file = dir.file("gm.txt");
  const auto sim = run_cli({"simulate", "--rate", "200", "--duration", "1800", "--N", "8.9e-4",
                            "--B", "5.9e-4", "--gm-sigma", "1.5e-3", "--gm-tau", "2",
                            "--units", "deg/s", "--seed", "4", "-o", file});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto r = run_cli({"fit", file, "--units", "deg/s", "--terms", "Q,N,B,K,GM,SIN"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // terms.GM is a list by correlation time: the wls fit's one term.
  ASSERT_TRUE(j["terms"]["GM"].is_array()) << j["terms"]["GM"];
  ASSERT_EQ(j["terms"]["GM"].size(), 1u);
  const auto& gm = j["terms"]["GM"][0];
  EXPECT_TRUE(gm["test"]["selected"].get<bool>()) << gm.dump();
  EXPECT_TRUE(gm["sigma"]["identified"].get<bool>());
  EXPECT_EQ(gm["sigma"]["unit"], "deg/s");
  EXPECT_EQ(gm["sigma"]["customary"]["unit"], "deg/h");
  EXPECT_NEAR(gm["sigma"]["value"].get<double>() / 1.5e-3, 1.0, 0.25);
  EXPECT_EQ(gm["correlation_time_s"]["unit"], "s");
  EXPECT_NEAR(gm["correlation_time_s"]["value"].get<double>() / 2.0, 1.0, 0.25);
  EXPECT_FALSE(j["terms"]["SIN"]["test"]["selected"].get<bool>());
  EXPECT_FALSE(j["terms"]["SIN"]["amplitude"]["identified"].get<bool>());
  EXPECT_EQ(r.out.find("NaN"), std::string::npos);
  bool gm_row = false;
  for (const auto& p : j["diagnostics"]["residuals"]) gm_row = gm_row || p["dominant_term"] == "GM";
  EXPECT_TRUE(gm_row);

  const auto t = run_cli({"fit", file, "--units", "deg/s", "--terms", "N,B,GM", "--format", "table"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("GMs"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("GMt"), std::string::npos) << t.out;
  EXPECT_EQ(t.out.find(" nan"), std::string::npos) << t.out;

  const auto o = run_cli({"fit", file, "--units", "deg/s", "--terms", "N,GM", "--method", "ols"});
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("wls"), std::string::npos) << o.err;
  const auto alone = run_cli({"fit", file, "--units", "deg/s", "--terms", "GM"});
  EXPECT_EQ(alone.exit_code, 1);
  EXPECT_NE(alone.err.find("power-law terms"), std::string::npos) << alone.err;
  EXPECT_TRUE(alone.out.empty());
}

// The fitted tau range, the excluded taus and the mismatch in the JSON, the built-in
// adis16405 spec, and a reversed range refused.
TEST(CliFit, TauRangeMismatchAndAdisSpec) {
  TempDir dir;
  const std::string file = dir.file("g.f64");
  const auto sim = run_cli({"simulate", "--rate", "200", "--duration", "1800", "--N", "8.9e-4",
                            "--B", "5.9e-4", "--units", "deg/s", "--seed", "5", "--format", "f64",
                            "-o", file});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto r = run_cli({"fit", file, "--binary", "f64", "--rate", "200", "--units", "deg/s",
                          "--tau-min", "0.02", "--tau-max", "100", "--spec", "adis16405"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& d = j["diagnostics"];
  ASSERT_TRUE(d["excluded_taus"].is_array());
  ASSERT_FALSE(d["excluded_taus"].empty());
  for (const auto& e : d["excluded_taus"]) {
    EXPECT_EQ(e["reason"], "tau_range");
    const double t = e["tau_s"].get<double>();
    EXPECT_TRUE(t < 0.02 || t > 100.0) << t;
  }
  for (const auto& p : d["residuals"]) {
    const double t = p["tau_s"].get<double>();
    EXPECT_EQ(p["used"].get<bool>(), t >= 0.02 && t <= 100.0) << t;
  }
  EXPECT_TRUE(d.contains("mismatch_scatter"));
  EXPECT_TRUE(d.contains("chi2_dof_with_mismatch"));
  EXPECT_EQ(j["spec_comparison"]["spec"], "adis16405");
  const auto t = run_cli({"fit", file, "--binary", "f64", "--rate", "200", "--format", "table",
                          "--tau-min", "0.02"});
  EXPECT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("excluded"), std::string::npos);

  const auto bad = run_cli({"fit", file, "--binary", "f64", "--rate", "200", "--tau-min", "10",
                            "--tau-max", "1"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("tau_max"), std::string::npos) << bad.err;
}

TEST(CliFit, BadInputGivesClearMessages) {
  TempDir dir;
  std::string zeros;
  for (int i = 0; i < 5000; ++i) zeros += "0\n";
  const auto z = run_cli({"fit", dir.write("zeros.txt", zeros), "--rate", "100"});
  EXPECT_EQ(z.exit_code, 1);
  EXPECT_NE(z.err.find("constant"), std::string::npos) << z.err;
  EXPECT_TRUE(z.out.empty());

  std::string few;
  for (int i = 0; i < 8; ++i) few += std::to_string(0.1 * ((i * 7) % 5)) + "\n";
  const auto f = run_cli({"fit", dir.write("few.txt", few), "--rate", "100"});
  EXPECT_EQ(f.exit_code, 1);
  EXPECT_NE(f.err.find("too few"), std::string::npos) << f.err;

  const auto m = run_cli({"fit", dir.write("x.txt", zeros), "--rate", "100", "--method", "lsq"});
  EXPECT_EQ(m.exit_code, 1);
  EXPECT_NE(m.err.find("wls, ols, slope or gmwm"), std::string::npos) << m.err;
  const auto t = run_cli({"fit", dir.file("x.txt"), "--rate", "100", "--terms", "N,X"});
  EXPECT_EQ(t.exit_code, 1);
  EXPECT_NE(t.err.find("unknown term"), std::string::npos) << t.err;
}

}  // namespace
}  // namespace imunoise

namespace imunoise {
namespace {

// A gyro with a 0.5 Hz sinusoid and a 30 s Gauss-Markov term on top of N and B: the power-law
// fit is rejected, so the default fit adds both terms by itself, says so, and their intervals
// hold the simulated truth; --no-auto-terms keeps the power laws alone.
TEST(CliFit, AutomaticTermsAndTheirSwitch) {
  test::TempDir dir;
  const std::string file = dir.file("bumpy.f64");
  const auto sim = test::run_cli({"simulate", "--rate", "200", "--duration", "1800", "--N", "8.9e-4",
                                  "--B", "5.9e-4", "--sine-amp", "0.02", "--sine-freq", "0.5",
                                  "--gm-sigma", "2e-3", "--gm-tau", "30", "--units", "deg/s",
                                  "--seed", "21", "--format", "f64", "-o", file});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const std::vector<std::string> fit{"fit", file, "--binary", "f64", "--rate", "200", "--units", "deg/s"};
  const auto r = test::run_cli(fit);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["terms"]["GM"].is_array() && j["terms"]["GM"].size() == 1) << j["terms"];
  const auto& gm = j["terms"]["GM"][0];
  const auto& sin = j["terms"]["SIN"];
  ASSERT_TRUE(gm["automatic"].is_string()) << gm;
  ASSERT_TRUE(sin["automatic"].is_string()) << sin;
  EXPECT_LE(gm["correlation_time_s"]["ci_low"].get<double>(), 30.0);
  EXPECT_GE(gm["correlation_time_s"]["ci_high"].get<double>(), 30.0);
  EXPECT_LE(sin["amplitude"]["ci_low"].get<double>(), 0.02);
  EXPECT_GE(sin["amplitude"]["ci_high"].get<double>(), 0.02);
  EXPECT_NE(r.err.find("added automatically"), std::string::npos) << r.err;

  auto off = fit;
  off.push_back("--no-auto-terms");
  const auto p = test::run_cli(off);
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const auto k = nlohmann::json::parse(p.out);
  EXPECT_FALSE(k["terms"].contains("GM")) << k["terms"];
  EXPECT_FALSE(k["terms"].contains("SIN")) << k["terms"];
  EXPECT_EQ(p.err.find("added automatically"), std::string::npos) << p.err;
}

}  // namespace
}  // namespace imunoise
