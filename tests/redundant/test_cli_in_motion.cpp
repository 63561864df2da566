// `imunoise redundant --in-motion F1 ... Fn` as a user runs it: recordings of a moving unit
// written as text files (deg/s), read through the loader; JSON in_motion.sensors one entry per
// file, the table, and the refusals (exit 1 naming the cause).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "redundant/redundant_test_support.hpp"
#include "study/browser_support.hpp"

namespace {

using imunoise::test::run_cli;
using imunoise::test::TempDir;
using namespace imunoise;
using namespace imunoise::redundant_test;

std::array<double, 3> tumbling(double t) {
  const double w = 200.0 * kDeg;
  return {w * std::sin(2 * std::numbers::pi * 0.5 * t), w * std::sin(2 * std::numbers::pi * 0.31 * t + 1.0),
          w * std::sin(2 * std::numbers::pi * 0.17 * t + 2.0)};
}

// One text file per sensor, deg/s, of a unit of `geometry` with white noise N_i = (1 + 0.2 i) 1e-3 deg/sqrt(s).
std::vector<std::string> write_unit(const TempDir& dir, const std::string& geometry, double duration_s,
                                    std::vector<double>* n_deg = nullptr) {
  const auto g = redundant::make_geometry(geometry);
  std::vector<sim::NoiseModel> models(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) models[i].n_unit_sqrt_s = 1e-3 * (1.0 + 0.2 * static_cast<double>(i));
  if (n_deg != nullptr) {
    n_deg->clear();
    for (const auto& m : models) n_deg->push_back(m.n_unit_sqrt_s);
  }
  const auto rec = simulate_unit(g, models, 100.0, duration_s, 77, tumbling);
  std::vector<std::string> files;
  for (std::size_t i = 0; i < rec.size(); ++i) {
    std::string text;
    for (double v : rec[i]) text += fmt::format("{:.17g}\n", v / kDeg);
    files.push_back(dir.write(fmt::format("{}_{}.txt", geometry.substr(0, 5), i + 1), text));
  }
  return files;
}

std::vector<std::string> in_motion_args(const std::string& geometry, const std::vector<std::string>& files) {
  std::vector<std::string> a{"redundant", "--geometry", geometry, "--in-motion"};
  a.insert(a.end(), files.begin(), files.end());
  for (const char* s : {"--rate", "100", "--units", "deg/s"}) a.emplace_back(s);
  return a;
}

TEST(CliRedundantInMotion, SixGyroUnitGivesEverySensorItsCurveAndFit) {
  TempDir dir;
  std::vector<double> n_deg;
  const auto files = write_unit(dir, "dodeca", 600.0, &n_deg);
  const auto r = run_cli(in_motion_args("dodeca", files));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["geometry"], "dodeca");
  const auto& im = j["in_motion"];
  EXPECT_EQ(im["unit"], "deg/s");
  EXPECT_TRUE(im["identifiability"]["per_sensor"].get<bool>());
  EXPECT_EQ(im["identifiability"]["rank"], 6);
  ASSERT_EQ(im["sensors"].size(), 6u);
  EXPECT_TRUE(im["leakage"]["removed"].get<bool>());
  EXPECT_EQ(im["leakage"]["coefficients"].size(), 3u);
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& s = im["sensors"][i];
    // Perfect sensors: what leaks is the regression's noise, a few ppm at most.
    EXPECT_LT(std::abs(s["leakage"]["scale_factor_ppm"].get<double>()), 20.0) << s.dump();
    EXPECT_EQ(s["source"], files[i]);
    ASSERT_TRUE(s["identified"].get<bool>());
    const auto& p0 = s["curve"]["points"][0];
    EXPECT_NEAR(p0["tau_s"].get<double>(), 0.01, 1e-12);
    // White noise: adev(tau0) = N / sqrt(tau0), in deg/s.
    EXPECT_NEAR(p0["adev"].get<double>(), n_deg[i] / std::sqrt(0.01), 0.03 * n_deg[i] / std::sqrt(0.01));
    EXPECT_LT(p0["ci_low"].get<double>(), p0["adev"].get<double>());
    EXPECT_GT(p0["ci_high"].get<double>(), p0["adev"].get<double>());
    ASSERT_TRUE(s["fit"].is_object()) << s.dump();
    EXPECT_NEAR(s["fit"]["terms"]["N"]["value"].get<double>(), n_deg[i], 0.05 * n_deg[i]) << i;
    EXPECT_EQ(s["fit"]["terms"]["N"]["unit"], "deg/sqrt(s)");
  }
  // The same sensors at rest: their fits and the in-motion / static ratio (here ~1: the same noise).
  std::vector<std::string> statics;
  for (std::size_t i = 0; i < 6; ++i) {
    sim::NoiseModel m;
    m.n_unit_sqrt_s = n_deg[i];
    std::string text;
    for (double v : sim::simulate(m, 100.0, 60000, 99, i)) text += fmt::format("{:.17g}\n", v);
    statics.push_back(dir.write(fmt::format("static_{}.txt", i + 1), text));
  }
  auto with_static = in_motion_args("dodeca", files);
  with_static.emplace_back("--static");
  with_static.insert(with_static.end(), statics.begin(), statics.end());
  const auto st = run_cli(with_static);
  ASSERT_EQ(st.exit_code, 0) << st.err;
  const auto sj = nlohmann::json::parse(st.out)["in_motion"]["sensors"];
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(sj[i]["static_fit"]["source"], statics[i]);
    const auto& n = sj[i]["inflation"]["N"];
    ASSERT_TRUE(n["ratio"].is_number()) << n.dump();
    EXPECT_NEAR(n["ratio"].get<double>(), 1.0, 0.05);
    EXPECT_LT(n["ci_low"].get<double>(), n["ci_high"].get<double>());
  }
  with_static.pop_back();
  const auto few = run_cli(with_static);
  EXPECT_EQ(few.exit_code, 1);
  EXPECT_NE(few.err.find("--static: 5 recordings for the 6 sensors"), std::string::npos) << few.err;

  auto table_args = in_motion_args("dodeca", files);
  table_args.insert(table_args.end(), {"--format", "table"});
  const auto t = run_cli(table_args);
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("sensor 6 ("), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("rank 6"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("deg/sqrt(s)"), std::string::npos) << t.out;
}

TEST(CliRedundantInMotion, TetrahedronReportsTheMeanLevelAndRefusesPerSensor) {
  TempDir dir;
  const auto files = write_unit(dir, "tetra", 60.0);
  const auto r = run_cli(in_motion_args("tetra", files));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto im = nlohmann::json::parse(r.out)["in_motion"];
  EXPECT_FALSE(im["identifiability"]["per_sensor"].get<bool>());
  ASSERT_EQ(im["sensors"].size(), 4u);
  for (const auto& s : im["sensors"]) {
    EXPECT_FALSE(s["identified"].get<bool>());
    EXPECT_FALSE(s.contains("curve"));
    EXPECT_NE(s["reason"].get<std::string>().find("fewer equations than sensors"), std::string::npos);
  }
  EXPECT_GT(im["common"]["points"].size(), 5u);
  for (const auto& w : im["common"]["weights"]) EXPECT_NEAR(w.get<double>(), 0.25, 1e-12);
  auto strict = in_motion_args("tetra", files);
  strict.emplace_back("--per-sensor");
  const auto s = run_cli(strict);
  EXPECT_EQ(s.exit_code, 1);
  EXPECT_NE(s.err.find("fewer equations than sensors"), std::string::npos) << s.err;
}

TEST(CliRedundantInMotion, BadInputExitsOneWithTheCause) {
  TempDir dir;
  auto files = write_unit(dir, "dodeca", 20.0);
  // A file count that does not match the geometry.
  auto five = files;
  five.pop_back();
  auto r = run_cli(in_motion_args("dodeca", five));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("5 recordings for the 6 sensors of geometry dodeca"), std::string::npos) << r.err;
  // A recording of another length (not synchronous).
  auto shorter = files;
  shorter[3] = dir.write("short.txt", "0.1\n0.2\n0.3\n0.1\n0.2\n0.3\n0.1\n0.2\n0.3\n0.4\n");
  r = run_cli(in_motion_args("dodeca", shorter));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("short.txt has 10 samples"), std::string::npos) << r.err;
  // Fewer sensors than the analysis needs: three axes, no parity space.
  const std::string triad = dir.write("triad.csv", "1,0,0\n0,1,0\n0,0,1\n");
  r = run_cli(in_motion_args(triad, {files[0], files[1], files[2]}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no parity space"), std::string::npos) << r.err;
  // No unit.
  std::vector<std::string> no_units{"redundant", "--geometry", "dodeca", "--rate", "100", "--in-motion"};
  no_units.insert(no_units.end(), files.begin(), files.end());
  r = run_cli(no_units);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--units"), std::string::npos) << r.err;
  // A confidence level given as a percentage.
  auto percent = in_motion_args("dodeca", files);
  percent.insert(percent.end(), {"--ci", "95"});
  r = run_cli(percent);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--ci 95"), std::string::npos) << r.err;
  // Not with --fuse.
  auto both = in_motion_args("dodeca", files);
  both.emplace_back("--fuse");
  both.insert(both.end(), files.begin(), files.end());
  r = run_cli(both);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cannot be combined"), std::string::npos) << r.err;
}

TEST(CliRedundantInMotion, ReportShowsEachSensorInMotionAndAtRestOnOneFigure) {
  TempDir dir;
  std::vector<double> n_deg;
  const auto files = write_unit(dir, "dodeca", 300.0, &n_deg);
  // At rest each sensor is 1.5 x quieter than in motion: the figure shows the gap.
  std::vector<std::string> statics;
  for (std::size_t i = 0; i < 6; ++i) {
    sim::NoiseModel m;
    m.n_unit_sqrt_s = n_deg[i] / 1.5;
    std::string text;
    for (double v : sim::simulate(m, 100.0, 30000, 5, i)) text += fmt::format("{:.17g}\n", v);
    statics.push_back(dir.write(fmt::format("rest_{}.txt", i + 1), text));
  }
  auto args = in_motion_args("dodeca", files);
  args.emplace_back("--static");
  args.insert(args.end(), statics.begin(), statics.end());
  const std::string out = dir.file("report");
  args.insert(args.end(), {"--report", out});
  const auto r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("wrote the in-motion report to"), std::string::npos) << r.err;
  namespace fs = std::filesystem;
  for (const char* f : {"report.json", "report.md", "report.html"}) EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  const auto doc = nlohmann::json::parse(imunoise::test::slurp(out + "/report.json"));
  const auto& figures = doc["figures"];
  ASSERT_EQ(figures.size(), 7u);  // six sensors and the mean level
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& f = figures[i];
    EXPECT_EQ(f["id"], fmt::format("in_motion_{}", i + 1));
    ASSERT_EQ(f["series"].size(), 4u) << f.dump();
    EXPECT_EQ(f["series"][0]["name"], "in motion (parity space)");
    EXPECT_EQ(f["series"][2]["name"], "at rest (static recording)");
    EXPECT_EQ(f["y_label"], "Allan deviation (deg/s)");
    // The two curves on the figure at their shortest tau: in motion 1.5 x the static level.
    const double moving = f["series"][0]["y"][0].get<double>();
    const double rest = f["series"][2]["y"][0].get<double>();
    std::printf("report figure %zu: in motion / at rest at tau0 %.4f (truth 1.5)\n", i + 1, moving / rest);
    EXPECT_NEAR(moving / rest, 1.5, 0.1) << "sensor " << i + 1;
    EXPECT_GT(f["series"][2]["x"].size(), 5u);
  }
  const std::string md = imunoise::test::slurp(out + "/report.md");
  EXPECT_NE(md.find("N ratio"), std::string::npos) << md;
  // An existing report is not replaced without --force.
  const auto again = run_cli(args);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  // As a person sees it: every figure drawn with its points, no script error.
  if (const std::string why = imunoise::test::browser_missing(); !why.empty()) {
    if (std::getenv("IMUNOISE_REQUIRE_BROWSER") != nullptr) FAIL() << why << " (required)";
    std::printf("browser check skipped: %s\n", why.c_str());
    return;
  }
  std::string log;
  const std::string dom = imunoise::test::dump_dom(fs::path(out) / "report.html", dir.file("browser"), &log);
  imunoise::test::expect_every_figure_drawn(dom, figures, log);
}

TEST(CliRedundantInMotion, SimulatedUnitFromTheCommandLineIsReadBack) {
  // imunoise simulate --unit writes one file per sensor; redundant --in-motion reads them back:
  // N recovered per sensor, and the 1000 ppm scale factor of sensor 1 seen as P_11 1000 = 500 ppm
  // (the dodecahedral unit's minimum-norm convention, docs/redundant.md).
  TempDir dir;
  const std::string out = dir.file("unit");
  const std::vector<std::string> sim{"simulate", "--unit", "dodeca", "--motion", "tumble:200+vibration:2:15",
                                     "--rate", "100", "--duration", "300", "--N", "1e-3", "--units", "deg/s",
                                     "--sensor-scale-ppm", "1000,0,0,0,0,0", "--seed", "5", "-o", out};
  const auto s = run_cli(sim);
  ASSERT_EQ(s.exit_code, 0) << s.err;
  std::vector<std::string> files;
  for (int i = 1; i <= 6; ++i) files.push_back(out + "/sensor" + std::to_string(i) + ".txt");
  const auto r = run_cli(in_motion_args("dodeca", files));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto im = nlohmann::json::parse(r.out)["in_motion"];
  ASSERT_EQ(im["samples"], 30000);
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& sensor = im["sensors"][i];
    EXPECT_NEAR(sensor["fit"]["terms"]["N"]["value"].get<double>(), 1e-3, 0.05e-3) << "sensor " << i + 1;
    const double sf = sensor["leakage"]["scale_factor_ppm"].get<double>();
    std::printf("simulate --unit round trip, sensor %zu: N %.5g deg/sqrt(s) (truth 1e-3), scale factor %.2f ppm\n",
                i + 1, sensor["fit"]["terms"]["N"]["value"].get<double>(), sf);
    EXPECT_NEAR(sf, i == 0 ? 500.0 : -100.0, 10.0) << "sensor " << i + 1;
  }
  // The same files again without --force, other output formats, a bad motion, a wrong count.
  auto again = run_cli(sim);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("sensor1.txt: file exists"), std::string::npos) << again.err;
  auto bad = sim;
  bad[4] = "spin:3";
  again = run_cli(bad);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--motion term 'spin:3' is not known"), std::string::npos) << again.err;
  bad = sim;
  bad[14] = "1000,0";
  again = run_cli(bad);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--sensor-scale-ppm: 2 values for the 6 sensors"), std::string::npos) << again.err;
  bad = sim;
  bad.insert(bad.end(), {"--format", "f64", "--force"});
  again = run_cli(bad);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--unit writes text files"), std::string::npos) << again.err;
  bad = sim;
  bad.insert(bad.end(), {"--range", "100", "--force"});
  again = run_cli(bad);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("--unit simulates rates"), std::string::npos) << again.err;
}

}  // namespace
