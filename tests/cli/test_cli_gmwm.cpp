// imunoise fit --method gmwm as a user runs it, and what comes after it: a record with two
// Gauss-Markov terms (the sum of two simulator runs: the simulator's channel has one GM term),
// the fit document's terms.GM list, the Kalman-filter states, what the Kalibr-style exports
// cannot carry, the navigation error, analyze and the table; and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace imunoise::test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::vector<double> read_f64(const std::string& path) {
  const std::string bytes = slurp(path);
  std::vector<double> v(bytes.size() / sizeof(double));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(double));
  return v;
}

void write_f64(const std::string& path, const std::vector<double>& v) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
}

// 2 h at 100 Hz, deg/s: white N 1e-3 deg/sqrt(s) + GM 5e-3 deg/s with T_c 1 s + GM 2e-3 deg/s
// with T_c 100 s. Each GM dominates the curve over a decade of tau (the fast one's Allan peak
// 3.1e-3 deg/s at 1.9 s against white 7e-4; the slow one's 1.2e-3 deg/s at 190 s against
// 5e-4 from the fast one and 7e-5 from white), and the slow T_c is 72 times inside the record.
struct TwoGaussMarkov {
  TempDir dir;
  std::string file;
  TwoGaussMarkov() {
    const std::string a = dir.file("a.f64"), b = dir.file("b.f64");
    const auto ra = run_cli({"simulate", "--rate", "100", "--duration", "7200", "--N", "1e-3", "--gm-sigma", "5e-3",
                             "--gm-tau", "1", "--units", "deg/s", "--seed", "31", "--format", "f64", "-o", a});
    EXPECT_EQ(ra.exit_code, 0) << ra.err;
    const auto rb = run_cli({"simulate", "--rate", "100", "--duration", "7200", "--gm-sigma", "2e-3", "--gm-tau",
                             "100", "--units", "deg/s", "--seed", "32", "--format", "f64", "-o", b});
    EXPECT_EQ(rb.exit_code, 0) << rb.err;
    std::vector<double> sum = read_f64(a);
    const std::vector<double> other = read_f64(b);
    EXPECT_EQ(sum.size(), other.size());
    for (std::size_t i = 0; i < sum.size() && i < other.size(); ++i) sum[i] += other[i];
    file = dir.file("two_gm.f64");
    write_f64(file, sum);
  }
  static const TwoGaussMarkov& shared() {
    static const TwoGaussMarkov record;
    return record;
  }
  std::vector<std::string> fit_args(std::vector<std::string> extra) const {
    std::vector<std::string> a{"fit", file, "--binary", "f64", "--rate", "100", "--units", "deg/s",
                               "--method", "gmwm", "--terms", "N,GM,GM"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
};

TEST(CliGmwm, EveryGaussMarkovTermReachesTheDocumentTheExportsAndTheNavigationError) {
  const auto& rec = TwoGaussMarkov::shared();
  TempDir dir;
  const std::string fit = dir.file("fit.json"), kf = dir.file("kf.json"), kalibr = dir.file("imu.yaml"),
                    openvins = dir.file("openvins.yaml");
  const auto r = run_cli(rec.fit_args({"--kf-json", kf, "--kalibr", kalibr, "--export", "openvins:" + openvins,
                                       "-o", fit}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(fit));
  // terms.GM: both terms, by correlation time, in the shape of the wls fit's one term.
  const auto& gm = doc["terms"]["GM"];
  ASSERT_TRUE(gm.is_array()) << doc["terms"];
  ASSERT_EQ(gm.size(), 2u) << gm;
  for (const auto& g : gm) {
    EXPECT_TRUE(g["sigma"]["identified"].get<bool>()) << g;
    EXPECT_TRUE(g["correlation_time_s"]["identified"].get<bool>()) << g;
    EXPECT_EQ(g["sigma"]["unit"], "deg/s");
    EXPECT_EQ(g["correlation_time_s"]["unit"], "s");
  }
  const double tc1 = gm[0]["correlation_time_s"]["value"].get<double>();
  const double tc2 = gm[1]["correlation_time_s"]["value"].get<double>();
  EXPECT_LT(tc1, tc2);
  // Loose: the test is of the plumbing (the estimator's accuracy is tests/fit/test_gmwm.cpp's).
  EXPECT_NEAR(std::log(tc1 / 1.0), 0.0, std::log(2.0)) << gm;
  EXPECT_NEAR(std::log(tc2 / 100.0), 0.0, std::log(3.0)) << gm;
  ASSERT_EQ(doc["gmwm"]["GM"].size(), 2u);
  EXPECT_DOUBLE_EQ(doc["gmwm"]["GM"][1]["sigma"]["value"].get<double>(), gm[1]["sigma"]["value"].get<double>());

  // Kalman-filter JSON: one state per GM term (SI), bias_instability the first of them.
  const auto k = nlohmann::json::parse(slurp(kf));
  const auto& states = k["gauss_markov_states"];
  ASSERT_EQ(states.size(), 2u) << k.dump(1);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(states[i]["sigma"]["value"].get<double>() / (gm[i]["sigma"]["value"].get<double>() * kDeg), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(states[i]["correlation_time"]["value"].get<double>(), gm[i]["correlation_time_s"]["value"].get<double>());
    EXPECT_EQ(states[i]["sigma"]["unit"], "rad/s");
  }
  EXPECT_DOUBLE_EQ(k["bias_instability"]["correlation_time"]["value"].get<double>(), tc1);

  // Kalibr and OpenVINS have no Gauss-Markov field: said in the file and on stderr.
  EXPECT_NE(slurp(kalibr).find("2 Gauss-Markov terms"), std::string::npos) << slurp(kalibr);
  EXPECT_NE(slurp(kalibr).find("not carried"), std::string::npos);
  EXPECT_NE(slurp(openvins).find("not carried"), std::string::npos) << slurp(openvins);
  EXPECT_NE(r.err.find("warning: --kalibr: 2 Gauss-Markov terms"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("warning: --export openvins:"), std::string::npos) << r.err;

  // The navigation error takes both terms: more than with the first alone.
  auto first_only = doc;
  first_only["terms"]["GM"].erase(1);
  const std::string one = dir.write("one.json", first_only.dump());
  const auto nav_both = run_cli({"nav", "--from", fit, "--model", "covariance", "--format", "json"});
  const auto nav_one = run_cli({"nav", "--from", one, "--model", "covariance", "--format", "json"});
  ASSERT_EQ(nav_both.exit_code, 0) << nav_both.err;
  ASSERT_EQ(nav_one.exit_code, 0) << nav_one.err;
  const auto both = nlohmann::json::parse(nav_both.out), first = nlohmann::json::parse(nav_one.out);
  EXPECT_EQ(both["axes"][1]["gauss_markov"].size(), 2u);
  EXPECT_GT(both["models"][0]["radial_m"].back().get<double>(), first["models"][0]["radial_m"].back().get<double>());

  // The table: a pair of rows per GM term.
  const auto t = run_cli(rec.fit_args({"--format", "table"}));
  ASSERT_EQ(t.exit_code, 0) << t.err;
  for (const char* row : {"GMs ", "GMt ", "GM2s", "GM2t"}) EXPECT_NE(t.out.find(row), std::string::npos) << row << t.out;
}

TEST(CliGmwm, AnalyzeFitsByGmwmAndItsFigureDrawsEveryGaussMarkovTerm) {
  const auto& rec = TwoGaussMarkov::shared();
  TempDir dir;
  const std::string out = dir.file("report");
  const auto r = run_cli({"analyze", rec.file, "--binary", "f64", "--rate", "100", "--units", "deg/s", "--method",
                          "gmwm", "--terms", "N,GM,GM", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The one line per channel names the gmwm model and its GM terms, not Q B K "not identified".
  EXPECT_NE(r.err.find("gmwm model N+GM+GM (GM T_c "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("not identified: Q"), std::string::npos) << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/report.json"));
  ASSERT_EQ(doc["channels"].size(), 1u);
  const auto& ch = doc["channels"][0];
  EXPECT_EQ(ch["fit"]["method"], "gmwm");
  ASSERT_TRUE(ch["fit"].contains("gmwm"));
  EXPECT_EQ(ch["fit"]["terms"]["GM"].size(), 2u);
  std::vector<std::string> symbols;
  for (const auto& term : ch["model"]["terms"]) symbols.push_back(term["symbol"].get<std::string>());
  EXPECT_NE(std::find(symbols.begin(), symbols.end(), "GM1"), symbols.end()) << ch["model"]["terms"];
  EXPECT_NE(std::find(symbols.begin(), symbols.end(), "GM2"), symbols.end()) << ch["model"]["terms"];
  // The model curve includes both: at the slow term's peak (tau ~ 190 s) it is above white +
  // the fast term alone (white 7e-5, fast 5e-4 deg/s there; the slow one adds ~1.2e-3).
  const auto& model = ch["model"];
  for (std::size_t i = 0; i < model["tau_s"].size(); ++i) {
    const double tau = model["tau_s"][i].get<double>();
    if (tau > 150.0 && tau < 250.0) {
      EXPECT_GT(model["adev"][i].get<double>(), 1e-3) << tau;
    }
  }
  // It is the model the fit matched: at each dyadic tau (log-log between the grid's points, a
  // factor 1.2 apart, where the curve bends by well under 1 %) it is sqrt(2 wv_model).
  const auto& scales = ch["fit"]["gmwm"]["wavelet_variance"];
  ASSERT_GT(scales.size(), 5u);
  std::size_t checked = 0;
  for (const auto& sc : scales) {
    const double tau = sc["tau_s"].get<double>();
    const double expect = std::sqrt(2.0 * sc["wv_model"].get<double>());
    for (std::size_t i = 0; i + 1 < model["tau_s"].size(); ++i) {
      const double t0 = model["tau_s"][i].get<double>(), t1 = model["tau_s"][i + 1].get<double>();
      if (!(t0 <= tau && tau <= t1)) continue;
      const double w = std::log(tau / t0) / std::log(t1 / t0);
      const double y = std::exp((1.0 - w) * std::log(model["adev"][i].get<double>()) +
                                w * std::log(model["adev"][i + 1].get<double>()));
      EXPECT_NEAR(y / expect, 1.0, 0.01) << "tau " << tau;
      ++checked;
      break;
    }
  }
  EXPECT_EQ(checked, scales.size());  // the grid spans the curve's taus
  // The report's tables: each GM term with its interval, the selection row, and the power-law
  // terms outside the model said to be so (not "not identified").
  const std::string md = slurp(out + "/report.md");
  EXPECT_NE(md.find("| GM1 | "), std::string::npos) << md;
  EXPECT_NE(md.find("| GM2 | "), std::string::npos) << md;
  EXPECT_NE(md.find("T_c = "), std::string::npos) << md;
  EXPECT_NE(md.find("### Model selection (gmwm)"), std::string::npos) << md;
  EXPECT_NE(md.find("| N+GM+GM | "), std::string::npos) << md;
  EXPECT_NE(md.find("– (not in the model)"), std::string::npos) << md;
  const std::string html = slurp(out + "/report.html");
  EXPECT_NE(html.find("<h2>Model selection (gmwm)</h2>"), std::string::npos);
  EXPECT_NE(html.find("not in the model"), std::string::npos);
}

TEST(CliGmwm, BadInputEndsWithAClearMessageOrATermNotIdentified) {
  TempDir dir;
  // 200 samples: 7 dyadic scales, too few for N + K + three GM terms (8 parameters).
  const std::string tiny = dir.file("tiny.txt");
  ASSERT_EQ(run_cli({"simulate", "--rate", "100", "--duration", "2", "--N", "1e-3", "--units", "deg/s", "--seed",
                     "5", "-o", tiny})
                .exit_code,
            0);
  const auto many = run_cli({"fit", tiny, "--rate", "100", "--units", "deg/s", "--method", "gmwm", "--terms", "N,K,GM,GM,GM"});
  EXPECT_EQ(many.exit_code, 1);
  EXPECT_NE(many.err.find("dyadic scales"), std::string::npos) << many.err;
  EXPECT_NE(many.err.find("use fewer terms"), std::string::npos) << many.err;
  EXPECT_TRUE(many.out.empty());
  // Unknown gmwm term, and --bootstrap without gmwm: exit 1 naming the fix.
  const auto unknown = run_cli({"fit", tiny, "--rate", "100", "--units", "deg/s", "--method", "gmwm", "--terms", "N,XY"});
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("XY"), std::string::npos) << unknown.err;
  const auto boot = run_cli({"fit", tiny, "--rate", "100", "--units", "deg/s", "--bootstrap", "10"});
  EXPECT_EQ(boot.exit_code, 1);
  EXPECT_NE(boot.err.find("--method gmwm"), std::string::npos) << boot.err;

  // White noise only, fitted with a GM term: the curve has no correlated part, so the GM term
  // is not identified (its T_c slides towards 0, where an AR1 is white noise: the fit may stop
  // unconverged, and then nothing is identified), with the reason, value 0 and no Kalman-filter
  // state -- never a number pulled from noise. --terms auto then picks N alone.
  const std::string white = dir.file("white.txt");
  ASSERT_EQ(run_cli({"simulate", "--rate", "100", "--duration", "1800", "--N", "1e-3", "--units", "deg/s",
                     "--seed", "6", "-o", white})
                .exit_code,
            0);
  const std::string kf = dir.file("kf.json");
  const auto w = run_cli({"fit", white, "--rate", "100", "--units", "deg/s", "--method", "gmwm", "--terms", "N,GM", "--kf-json", kf});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const auto doc = nlohmann::json::parse(w.out);
  ASSERT_EQ(doc["terms"]["GM"].size(), 1u) << doc["terms"];
  const auto& g = doc["terms"]["GM"][0];
  EXPECT_FALSE(g["sigma"]["identified"].get<bool>()) << g;
  EXPECT_EQ(g["sigma"]["value"].get<double>(), 0.0);
  EXPECT_EQ(g["correlation_time_s"]["value"].get<double>(), 0.0);
  EXPECT_NE(g["correlation_time_s"]["note"].get<std::string>().find("best trial value"), std::string::npos)
      << g["correlation_time_s"];
  EXPECT_FALSE(g["sigma"]["note"].get<std::string>().empty());
  const auto& n = doc["terms"]["N"];
  if (!n["identified"].get<bool>()) {
    EXPECT_NE(n["note"].get<std::string>().find("fix:"), std::string::npos) << n;
  }
  EXPECT_TRUE(nlohmann::json::parse(slurp(kf))["gauss_markov_states"].empty());
  const auto a = run_cli({"fit", white, "--rate", "100", "--units", "deg/s", "--method", "gmwm", "--terms", "auto"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto auto_doc = nlohmann::json::parse(a.out);
  EXPECT_EQ(auto_doc["gmwm"]["model"], "N") << auto_doc["gmwm"]["candidates"];
  EXPECT_TRUE(auto_doc["terms"]["N"]["identified"].get<bool>());
  EXPECT_FALSE(auto_doc["terms"].contains("GM"));
}

// --terms N,BGM,K: flicker written as Gauss-Markov states. The states are in the fit document
// (gmwm section and terms.GM, marked part_of BGM), in the Kalman-filter JSON (one state each,
// SI) and B is not also reported as the power-law B (it would be counted twice downstream).
TEST(CliGmwm, FlickerAsGaussMarkovStatesReachesTheKalmanFilterJson) {
  TempDir dir;
  const std::string rec = dir.file("flicker.f64");
  ASSERT_EQ(run_cli({"simulate", "--rate", "100", "--duration", "1800", "--N", "1e-3", "--B", "2e-3", "--K", "1e-5",
                     "--units", "deg/s", "--seed", "12", "--format", "f64", "-o", rec})
                .exit_code,
            0);
  const std::string kf = dir.file("kf.json");
  const auto r = run_cli({"fit", rec, "--binary", "f64", "--rate", "100", "--units", "deg/s", "--method", "gmwm",
                          "--terms", "N,BGM,K", "--kf-json", kf});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  const auto& g = doc["gmwm"];
  EXPECT_EQ(g["model"], "N+BGM+K");
  const auto& mix = g["flicker_mixture"];
  const std::size_t count = mix["states"].get<std::size_t>();
  ASSERT_GE(count, 4u) << mix;
  EXPECT_LT(mix["ripple"].get<double>(), 0.03);
  nlohmann::json bgm;
  for (const auto& t : g["terms"]) {
    if (t["term"] == "BGM") bgm = t;
  }
  ASSERT_FALSE(bgm.is_null()) << g["terms"];
  ASSERT_TRUE(bgm["identified"].get<bool>()) << bgm;
  EXPECT_EQ(bgm["unit"], "deg/s");
  // Loose (plumbing; the estimator's accuracy is tests/fit/test_gmwm_flicker.cpp's).
  EXPECT_NEAR(std::log(bgm["value"].get<double>() / 2e-3), 0.0, std::log(1.5)) << bgm;
  ASSERT_EQ(bgm["states"].size(), count);
  EXPECT_FALSE(doc["terms"]["B"]["identified"].get<bool>());
  EXPECT_NE(doc["terms"]["B"]["note"].get<std::string>().find("BGM"), std::string::npos) << doc["terms"]["B"];
  ASSERT_EQ(doc["terms"]["GM"].size(), count) << doc["terms"];
  for (const auto& s : doc["terms"]["GM"]) EXPECT_EQ(s["part_of"], "BGM") << s;
  const auto k = nlohmann::json::parse(slurp(kf));
  const auto& states = k["gauss_markov_states"];
  ASSERT_EQ(states.size(), count) << k.dump(1);
  for (std::size_t i = 0; i < count; ++i) {
    const auto& mine = bgm["states"][i];
    EXPECT_NEAR(states[i]["sigma"]["value"].get<double>() / (mine["sigma"]["value"].get<double>() * kDeg), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(states[i]["correlation_time"]["value"].get<double>(),
                     mix["correlation_time_s"][i].get<double>());
    EXPECT_DOUBLE_EQ(mine["correlation_time_s"]["value"].get<double>(), mix["correlation_time_s"][i].get<double>());
  }
  // B and BGM together: exit 1 naming the clash.
  const auto both = run_cli({"fit", rec, "--binary", "f64", "--rate", "100", "--units", "deg/s", "--method", "gmwm",
                             "--terms", "N,B,BGM"});
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_NE(both.err.find("BGM"), std::string::npos) << both.err;
}

TEST(CliGmwm, RobustNeedsGmwmAndSaysSoInTheDocument) {
  TempDir dir;
  const std::string white = dir.file("white.txt");
  ASSERT_EQ(run_cli({"simulate", "--rate", "100", "--duration", "600", "--N", "1e-3", "--units", "deg/s", "--seed",
                     "8", "-o", white})
                .exit_code,
            0);
  const auto r = run_cli({"fit", white, "--rate", "100", "--units", "deg/s", "--method", "gmwm", "--terms", "N",
                          "--robust"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_TRUE(doc["gmwm"]["robust"].get<bool>());
  EXPECT_NEAR(doc["gmwm"]["robust_estimator"]["efficiency"].get<double>(), 0.6, 1e-9);
  EXPECT_GT(doc["gmwm"]["robust_estimator"]["tuning_constant"].get<double>(), 1.5);
  EXPECT_TRUE(doc["terms"]["N"]["identified"].get<bool>());
  EXPECT_NEAR(std::log(doc["terms"]["N"]["value"].get<double>() / 1e-3), 0.0, std::log(1.05)) << doc["terms"]["N"];
  // Without it: robust false, no estimator block.
  const auto c = run_cli({"fit", white, "--rate", "100", "--units", "deg/s", "--method", "gmwm", "--terms", "N"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_FALSE(nlohmann::json::parse(c.out)["gmwm"]["robust"].get<bool>());
  // --robust without --method gmwm: exit 1 naming the fix, nothing on standard output.
  const auto bad = run_cli({"fit", white, "--rate", "100", "--units", "deg/s", "--robust"});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--robust needs --method gmwm"), std::string::npos) << bad.err;
  EXPECT_TRUE(bad.out.empty());
}

}  // namespace
}  // namespace imunoise::test
