// `imunoise fleet` serial and under mpirun -np 2 / 3: byte-identical outputs, keep-going and
// --strict, a rank that dies ends the run (no hang), mixed rates, outputs never overwritten.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "fleet/mpi_runner.hpp"
#include "imunoise/fleet/report.hpp"
#include "study/browser_support.hpp"

namespace imunoise::test {
namespace {

std::string fmt_pass(const nlohmann::json& ds) {
  char text[128];
  std::snprintf(text, sizeof text, "%d of %d pass tg100 (%.1f %%)", ds["n_pass"].get<int>(),
                ds["n_judged"].get<int>(), 100.0 * ds["n_pass"].get<double>() / ds["n_judged"].get<double>());
  return text;
}

// Six gyros of one batch (white noise N near 7e-4 deg/sqrt(s) = 0.042 deg/sqrt(h), one at
// 9.5e-4), a seventh at another rate with N = 4e-3, and a file that is not a record.
struct Fleet {
  TempDir dir;
  std::vector<std::string> files;
  Fleet() {
    const double n[] = {7.0e-4, 7.2e-4, 6.9e-4, 9.5e-4, 7.1e-4, 6.8e-4};
    for (int i = 0; i < 6; ++i) {
      const std::string file = dir.file("s" + std::to_string(i + 1) + ".txt");
      const auto r = run_cli({"simulate", "--rate", "100", "--duration", "1200", "--N",
                              std::to_string(n[i]), "--B", "0.0003", "--K", "2e-6", "--seed",
                              std::to_string(i + 1), "-o", file});
      EXPECT_EQ(r.exit_code, 0) << r.err;
      files.push_back(file);
      if (i == 2) {
        files.push_back(dir.write("broken.txt", "0.1\n0.2\nnot-a-number\n"));
      }
    }
    const std::string odd = dir.file("odd50hz.txt");
    const auto r = run_cli({"simulate", "--rate", "50", "--duration", "1200", "--N", "0.004",
                            "--B", "0.0003", "--seed", "11", "-o", odd});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    files.push_back(odd);
  }
  /// One fleet for every test (its files are only read; each test writes its own outputs).
  static const Fleet& shared() {
    static const Fleet fleet;
    return fleet;
  }
  std::vector<std::string> args(const std::string& out, std::vector<std::string> extra = {}) const {
    std::vector<std::string> a{"fleet"};
    a.insert(a.end(), files.begin(), files.end());
    for (const auto& s : {"--units", "deg/s", "--spec", "tg100", "-o"}) a.emplace_back(s);
    a.push_back(out);
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
};

TEST(FleetCli, SerialRunReportsDistributionsOutliersAndGoesOnPastABadFile) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  const auto r = run_cli(fleet.args(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("broken.txt:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the fleet run goes on"), std::string::npos);
  const auto doc = nlohmann::json::parse(slurp(out + "/fleet.json"));
  ASSERT_EQ(doc["sensors"].size(), 8u);
  EXPECT_EQ(doc["summary"]["n_failed"], 1);
  EXPECT_EQ(doc["sensors"][3]["flags"], nlohmann::json({"error"}));
  // Mixed rates: each file at its own rate (from its header).
  EXPECT_EQ(doc["summary"]["rates_hz"], nlohmann::json({50.0, 100.0}));
  EXPECT_EQ(doc["sensors"][7]["fit"]["rate_hz"], 50.0);
  // The 9.5e-4 gyro (0.057 deg/sqrt(h)) and the 4e-3 one are outliers on N and fail the
  // datasheet's 0.05 deg/sqrt(h); the batch's typical gyros pass.
  for (const int i : {4, 7}) {
    const auto& flags = doc["sensors"][i]["flags"];
    EXPECT_NE(std::find(flags.begin(), flags.end(), "outlier"), flags.end()) << i;
    EXPECT_NE(std::find(flags.begin(), flags.end(), "datasheet_fail"), flags.end()) << i;
    EXPECT_NE(doc["sensors"][i]["reasons"][0].get<std::string>().find("N = "), std::string::npos);
  }
  for (const int i : {1, 2, 5, 6}) EXPECT_TRUE(doc["sensors"][i]["flags"].empty()) << i << doc["sensors"][i]["flags"];
  const auto& n = doc["summary"]["coefficients"]["N"];
  EXPECT_EQ(n["n_identified"], 7);
  EXPECT_NEAR(n["distribution"]["median"].get<double>(), 7.1e-4, 0.03 * 7.1e-4);
  EXPECT_GT(doc["summary"]["datasheet"]["pass_rate"].get<double>(), 0.5);
  const std::string csv = slurp(out + "/fleet.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
  // The report: the pass rate and distributions of fleet.json, the outliers with their reasons,
  // the failed file, the figures as files.
  const std::string md = slurp(out + "/report.md");
  const auto& ds = doc["summary"]["datasheet"];
  EXPECT_NE(md.find(fmt_pass(ds)), std::string::npos) << md;
  EXPECT_NE(md.find("| N | " + n["unit"].get<std::string>() + " | 7 | 0 |"), std::string::npos) << md;
  for (const std::string sensor : {"s4.txt", "odd50hz.txt"}) {
    const std::regex row("\\| " + std::regex_replace(sensor, std::regex("\\."), "\\.") +
                         " \\| [^|]*outlier[^|]*\\| N = [^|]*is an outlier: robust z");
    EXPECT_TRUE(std::regex_search(md, row)) << sensor << "\n" << md;
  }
  EXPECT_NE(md.find("broken.txt:3"), std::string::npos);
  for (const char* f : {"report.html", "figures/fleet_adev.svg", "figures/fleet_adev.png",
                        "figures/fleet_N.svg", "figures/fleet_B.png"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  }
  // Nothing is overwritten without --force.
  const auto again = run_cli(fleet.args(out));
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("fleet.json: file exists"), std::string::npos) << again.err;
  std::filesystem::remove(out + "/fleet.json");
  std::filesystem::remove(out + "/fleet.csv");
  const auto report_kept = run_cli(fleet.args(out));
  EXPECT_EQ(report_kept.exit_code, 1);
  EXPECT_NE(report_kept.err.find("already holds report.html"), std::string::npos) << report_kept.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/fleet.json")) << "refused before any work";
  EXPECT_EQ(run_cli(fleet.args(out, {"--force"})).exit_code, 0);
}

// The fleet report's figures describe the fleet document: the box is the fleet's quantiles,
// the datasheet line the TG-100's 0.05 deg/sqrt(h) (tolerance 0) in deg/s*sqrt(s), the outliers
// are named, every typical sensor is in the grey trace; the page draws them all in Chromium.
TEST(FleetReport, FiguresShowTheFleetAndTheBrowserDrawsThem) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  ASSERT_EQ(run_cli(fleet.args(out)).exit_code, 0);
  const auto doc = nlohmann::json::parse(slurp(out + "/fleet.json"));
  const auto figures = fleet::fleet_figures(doc);
  std::map<std::string, nlohmann::json> by_id;
  for (const auto& f : figures) by_id[f["id"].get<std::string>()] = f;
  ASSERT_TRUE(by_id.count("fleet_adev") && by_id.count("fleet_N") && by_id.count("fleet_B")) << figures.dump();
  EXPECT_FALSE(by_id.count("fleet_Q")) << "Q is not fitted by default";
  // Overlay: the typical sensors in one trace (7 analysed less the outliers), each outlier
  // named with the coefficients that make it one (s4 and odd50hz on N; s1 on B).
  const auto& overlay = by_id["fleet_adev"]["series"];
  const std::size_t outliers = doc["summary"]["outliers"].size();
  ASSERT_GE(outliers, 2u);
  EXPECT_EQ(overlay[0]["name"], std::to_string(7 - outliers) + " typical sensors");
  std::size_t separators = 0;
  for (const auto& y : overlay[0]["y"]) separators += y.is_null() ? 1 : 0;
  EXPECT_EQ(separators, 7 - outliers - 1);
  std::vector<std::string> names;
  for (const auto& s : overlay) names.push_back(s["name"].get<std::string>());
  EXPECT_NE(std::find(names.begin(), names.end(), "outlier s4.txt (N)"), names.end()) << overlay.dump();
  EXPECT_NE(std::find(names.begin(), names.end(), "outlier odd50hz.txt (N)"), names.end());
  std::size_t named = 0;
  for (const auto& n : names) named += n.rfind("outlier ", 0) == 0 && n.find(" model") == std::string::npos ? 1 : 0;
  EXPECT_EQ(named, outliers);
  // Coefficient N: the box's y values are the fleet's 5/25/50/75/95 % points.
  const auto& dist = doc["summary"]["coefficients"]["N"]["distribution"];
  const nlohmann::json* box = nullptr;
  const nlohmann::json* limit = nullptr;
  for (const auto& s : by_id["fleet_N"]["series"]) {
    if (s["name"].get<std::string>().rfind("box", 0) == 0) box = &s;
    if (s["name"].get<std::string>().rfind("datasheet N", 0) == 0) limit = &s;
  }
  ASSERT_NE(box, nullptr);
  for (const char* q : {"p05", "q25", "median", "q75", "p95"}) {
    EXPECT_NE(std::find((*box)["y"].begin(), (*box)["y"].end(), dist[q]), (*box)["y"].end()) << q;
  }
  ASSERT_NE(limit, nullptr);
  EXPECT_NEAR((*limit)["y"][0].get<double>(), 0.05 / 60.0, 1e-12);
  std::size_t points = 0;
  for (const auto& s : by_id["fleet_N"]["series"]) points += s["style"] == "points" ? s["x"].size() : 0;
  EXPECT_EQ(points, 7u);
  // The page as a person sees it.
  IMUNOISE_REQUIRE_BROWSER_OR_SKIP();
  std::string log;
  const std::string dom = dump_dom(out + "/report.html", out_dir.file("chromium"), &log);
  expect_every_figure_drawn(dom, figures, log);
}


// fleet --nav: each gyro's navigation error at 1 h is what `imunoise nav --from` computes from
// that sensor's fit document (the study's models, latitude and steps); the summary holds its
// quantiles, the CSV a column per model, the report a table and a figure.
// --method gmwm reaches every sensor's fit (the fit options are the fit command's).
TEST(FleetCli, MethodGmwmReachesEverySensorsFit) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  const auto r = run_cli(fleet.args(out, {"--method", "gmwm", "--terms", "N,K"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/fleet.json"));
  int gmwm = 0;
  for (const auto& s : doc["sensors"]) {
    if (s["fit"].is_null()) continue;  // the file that is not a record
    EXPECT_EQ(s["fit"]["method"], "gmwm");
    EXPECT_EQ(s["fit"]["gmwm"]["model"], "N+K");
    ++gmwm;
  }
  EXPECT_EQ(gmwm, 7);
  EXPECT_EQ(doc["summary"]["coefficients"]["N"]["n_identified"], 7);
  // --robust too: every sensor's fit says it is the robust GMWM.
  const std::string robust_out = out_dir.file("robust");
  const auto robust = run_cli(fleet.args(robust_out, {"--method", "gmwm", "--terms", "N,K", "--robust"}));
  ASSERT_EQ(robust.exit_code, 0) << robust.err;
  int robust_fits = 0;
  const auto robust_doc = nlohmann::json::parse(slurp(robust_out + "/fleet.json"));
  for (const auto& s : robust_doc["sensors"]) {
    if (s["fit"].is_null()) continue;
    EXPECT_TRUE(s["fit"]["gmwm"]["robust"].get<bool>());
    ++robust_fits;
  }
  EXPECT_EQ(robust_fits, 7);
}

TEST(FleetCli, NavigationErrorPerSensorAndItsDistribution) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  const auto r = run_cli(fleet.args(out, {"--nav"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/fleet.json"));
  const auto& summary = doc["summary"]["nav"];
  EXPECT_EQ(summary["t_s"], 3600.0);
  EXPECT_EQ(summary["n_sensors"], 7);
  std::vector<double> covariance_path;
  for (const int i : {0, 7}) {
    const auto& fit = doc["sensors"][i]["fit"];
    const std::string fit_file = out_dir.file("fit" + std::to_string(i) + ".json");
    std::ofstream(fit_file) << fit.dump();
    const auto nav = run_cli({"nav", "--from", fit_file, "--hours", "1", "--latitude", "58.5", "--step", "60",
                              "--dt", "1", "--model", "schuler,covariance", "--format", "json"});
    ASSERT_EQ(nav.exit_code, 0) << nav.err;
    const auto expected = nlohmann::json::parse(nav.out);
    ASSERT_EQ(fit["nav"]["models"].size(), expected["models"].size());
    for (std::size_t m = 0; m < expected["models"].size(); ++m) {
      const auto& e = expected["models"][m];
      const auto& got = fit["nav"]["models"][m];
      EXPECT_EQ(got["model"], e["model"]);
      const double want = e["path_m"].back().get<double>();
      EXPECT_NEAR(got["path_m"].get<double>(), want, 1e-9 * want) << got["model"];
      EXPECT_NEAR(got["lat_deg"].get<double>(), e["lat_deg"].back().get<double>(),
                  1e-9 * e["lat_deg"].back().get<double>());
    }
  }
  for (const auto& s : doc["sensors"]) {
    if (s["fit"].is_null()) continue;
    for (const auto& m : s["fit"]["nav"]["models"]) {
      if (m["model"] == "covariance") covariance_path.push_back(m["path_m"].get<double>());
    }
  }
  ASSERT_EQ(covariance_path.size(), 7u);
  std::sort(covariance_path.begin(), covariance_path.end());
  for (const auto& m : summary["models"]) {
    if (m["model"] == "covariance") EXPECT_EQ(m["path_m"]["median"].get<double>(), covariance_path[3]);
  }
  const std::string csv = slurp(out + "/fleet.csv");
  EXPECT_NE(csv.find(",nav_covariance_path_m,nav_covariance_lat_deg,nav_covariance_lon_deg"), std::string::npos);
  const std::string md = slurp(out + "/report.md");
  EXPECT_NE(md.find("## Navigation error after 1 h"), std::string::npos) << md;
  EXPECT_NE(md.find("figures/fleet_nav.svg"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out + "/figures/fleet_nav.png"));
}

// --nav on records that are not angular rates with a unit: each sensor says why it has no
// navigation error, the summary counts them, the report says so; a bad horizon is refused.
TEST(FleetCli, NavigationNotComputedIsReportedPerSensor) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  const auto r = run_cli({"fleet", fleet.files[0], fleet.files[1], "--nav", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(slurp(out + "/fleet.json"));
  for (const auto& s : doc["sensors"]) {
    EXPECT_NE(s["fit"]["nav"]["error"].get<std::string>().find("not an angular rate with a unit"),
              std::string::npos) << s["fit"]["nav"];
  }
  EXPECT_EQ(doc["summary"]["nav"]["n_sensors"], 0);
  EXPECT_EQ(doc["summary"]["nav"]["n_not_computed"], 2);
  EXPECT_EQ(doc["summary"]["nav"]["t_s"], 3600.0);
  EXPECT_NE(slurp(out + "/report.md").find("(2 not computed: not an angular rate with a unit)"), std::string::npos);
  const auto bad = run_cli({"fleet", fleet.files[0], "--units", "deg/s", "--nav", "--nav-hours", "0", "-o",
                            out_dir.file("bad")});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--nav-hours must be positive"), std::string::npos) << bad.err;
}

// A fleet of which no file can be analysed still gets its report: the failed file and why,
// no figure (nothing to draw), no made-up distribution.
TEST(FleetCli, ReportOfAFleetWithNothingAnalysed) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const std::string out = out_dir.file("out");
  const auto r = run_cli({"fleet", fleet.files[3], "--units", "deg/s", "--spec", "tg100", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = slurp(out + "/report.md");
  EXPECT_NE(md.find("broken.txt | "), std::string::npos) << md;
  EXPECT_NE(md.find("broken.txt:3: column 0"), std::string::npos) << md;
  EXPECT_NE(md.find("0 analysed, 1 failed"), std::string::npos);
  EXPECT_EQ(md.find("![") , std::string::npos) << "no figure";
  EXPECT_TRUE(fleet::fleet_figures(nlohmann::json::parse(slurp(out + "/fleet.json"))).empty());
}

TEST(FleetCli, StrictStopsAtTheFirstBadFile) {
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto r = run_cli(fleet.args(out_dir.file("out"), {"--strict"}));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.txt:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--strict"), std::string::npos) << r.err;
}

class FleetRanks : public ::testing::TestWithParam<int> {};

TEST_P(FleetRanks, OutputsAreTheSerialRunsBytes) {
  IMUNOISE_REQUIRE_MPI();
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto serial = run_cli(fleet.args(out_dir.file("serial"), {"--nav"}));
  ASSERT_EQ(serial.exit_code, 0) << serial.err;
  const auto parallel = run_mpi(GetParam(), fleet.args(out_dir.file("parallel"), {"--nav"}));
  ASSERT_EQ(parallel.exit_code, 0) << parallel.err;
  EXPECT_EQ(slurp(out_dir.file("parallel/fleet.json")), slurp(out_dir.file("serial/fleet.json")));
  EXPECT_EQ(slurp(out_dir.file("parallel/fleet.csv")), slurp(out_dir.file("serial/fleet.csv")));
  // The report too, figures included.
  std::size_t compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(out_dir.file("serial"))) {
    if (!entry.is_regular_file()) continue;
    const auto rel = std::filesystem::relative(entry.path(), out_dir.file("serial")).string();
    EXPECT_EQ(slurp(out_dir.file("parallel/" + rel)), slurp(entry.path().string())) << rel;
    ++compared;
  }
  EXPECT_GE(compared, 2u + 2u + 2u * 4u) << "fleet.json/csv, report.html/md, four figures";
  EXPECT_NE(parallel.err.find("broken.txt:3"), std::string::npos) << parallel.err;
}

TEST_P(FleetRanks, StrictStopsEveryRank) {
  IMUNOISE_REQUIRE_MPI();
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto r = run_mpi(GetParam(), fleet.args(out_dir.file("out"), {"--strict"}), 60);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("broken.txt:3"), std::string::npos) << r.err;
}

TEST_P(FleetRanks, ARankThatDiesFailsTheRunWithoutHanging) {
  IMUNOISE_REQUIRE_MPI();
  const Fleet& fleet = Fleet::shared();
  TempDir out_dir;
  const auto r = run_mpi(GetParam(), fleet.args(out_dir.file("out")), 60,
                         "IMUNOISE_TEST_RANK_DIES_ON=s5.txt");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 124) << "the run hung";
  // mpirun names the rank that died and the signal.
  EXPECT_NE(r.err.find("signal 9"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out_dir.file("out/fleet.json")));
}

INSTANTIATE_TEST_SUITE_P(Fleet, FleetRanks, ::testing::Values(2, 3));

}  // namespace
}  // namespace imunoise::test
