// The study pipeline: its document holds exactly the library's numbers, channels that cannot
// be studied together are refused, keep_going keeps the good channels, and the report
// directory is written completely or not at all.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <span>
#include <sstream>

#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/preprocess/dynamic_allan.hpp"
#include "imunoise/units.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/redundant/report.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/study/render.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"
#include "study_support.hpp"

namespace imunoise {
namespace {

namespace fs = std::filesystem;
using test::simulated_gyro;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct ScratchDir {
  fs::path path = fs::temp_directory_path() /
                  ("imunoise-study-" + std::to_string(::getpid()) + "-" +
                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  ScratchDir() { fs::remove_all(path); fs::create_directories(path); }
  ~ScratchDir() { fs::remove_all(path); }
};

// Two 30-minute gyros at 100 Hz: long enough for N, B-free, K weak; fast to study.
std::vector<study::Record> two_gyros() {
  return {simulated_gyro("gx", 8.9e-4, 1.5e-5, 100.0, 1800.0, 11),
          simulated_gyro("gy", 8.6e-4, 1.2e-5, 100.0, 1800.0, 12)};
}

study::StudyOptions options_with_spec() {
  study::StudyOptions o;
  o.spec = builtin_spec("tg100");
  return o;
}

TEST(Study, DocumentHoldsTheLibrarysNumbers) {
  auto records = two_gyros();
  const auto copy = records;  // the study consumes the samples
  const auto options = options_with_spec();
  const auto result = study::run_study(std::move(records), options);
  const auto doc = study::study_json(result);
  ASSERT_EQ(doc["channels"].size(), 2u);
  for (std::size_t c = 0; c < copy.size(); ++c) {
    const auto& ch = doc["channels"][c];
    EXPECT_EQ(ch["name"], copy[c].name);
    // Fit: the same JSON as the fit stage run on its own.
    const auto fit = study::fit_channel(copy[c], options.fit, options.fit_grid);
    EXPECT_EQ(ch["fit"], fit::report_json(study::record_info(copy[c]), options.fit, fit));
    // Curves: the same as the curve stage (oadev put first).
    study::CurveOptions co = options.curves;
    const auto curves = study::compute_curves(copy[c], co);
    EXPECT_EQ(ch["curves"], study::curves_json(copy[c], curves));
    // Datasheet comparison: the library's.
    EXPECT_EQ(ch["spec_comparison"], comparison_json(compare(fit.coefficients, *options.spec)));
    // The model line is eq. 5 of the fitted coefficients, in deg/s.
    const auto& model = ch["model"];
    const double to_si = parse_unit("deg/s").to_si;
    for (std::size_t i = 0; i < model["tau_s"].size(); i += 17) {
      const double tau = model["tau_s"][i];
      const double n = fit.coefficients.random_walk.value;
      const double k = fit.coefficients.rate_random_walk.value;
      const double b = fit.coefficients.bias_instability.value;
      const double q = fit.coefficients.quantization.value;
      const double expected = std::sqrt(3 * q * q / (tau * tau) + n * n / tau +
                                        2 * std::log(2.0) / M_PI * b * b + k * k * tau / 3) /
                              to_si;
      EXPECT_NEAR(model["adev"][i].get<double>(), expected, 1e-12 * expected) << tau;
    }
    // N's asymptote passes through N at tau = 1 s (IEEE 952 read-off), labelled in deg/sqrt(h).
    bool found = false;
    for (const auto& t : model["terms"]) {
      if (t["symbol"] != "N") continue;
      found = true;
      EXPECT_NEAR(t["anchor"]["tau_s"].get<double>(), 1.0, 1e-12);
      EXPECT_NEAR(t["anchor"]["adev"].get<double>(), fit.coefficients.random_walk.value / to_si,
                  1e-12);
      EXPECT_NE(t["label"].get<std::string>().find("deg/sqrt(h)"), std::string::npos);
    }
    EXPECT_TRUE(found);
    // Navigation: the nav module's document for this fit on all three axes.
    nav::NavOptions no;
    for (auto& axis : no.axes) axis.coefficients = fit.coefficients;
    no.duration_s = 3600.0;
    no.step_s = 60.0;
    no.dt_s = 1.0;
    no.latitude_rad = 58.5 * M_PI / 180.0;
    no.models = nav::parse_models("schuler,covariance,montecarlo");
    EXPECT_EQ(ch["nav"], nav::report_json(nav::navigation_error(no)));
  }
}

TEST(Study, RedundantUnitIsTheModulesAnalysisAndItsFusedAxesMatchIt) {
  std::vector<study::Record> records;
  for (int i = 0; i < 4; ++i) {
    records.push_back(simulated_gyro("g" + std::to_string(i + 1), 8.8e-4, 1e-5, 100.0, 1800.0,
                                     static_cast<std::uint64_t>(31 + i)));
  }
  auto copy = records;
  study::StudyOptions o;
  o.geometry = "tetra";
  const auto result = study::run_study(std::move(records), o);
  const auto doc = study::study_json(result);
  std::vector<redundant::SensorModel> sensors;
  for (const auto& ch : result.channels) sensors.push_back({ch.record.name, ch.fit->coefficients});
  // The module's analysis, and its detector run over the same rates (the phase's differences).
  const auto analysis = redundant::analyze_unit(redundant::make_geometry("tetra"), sensors);
  std::vector<std::vector<double>> rates;
  std::vector<std::span<const double>> spans;
  for (const auto& r : copy) {
    std::vector<double> rate(r.phase_si.size() - 1);
    for (std::size_t k = 0; k < rate.size(); ++k) rate[k] = (r.phase_si[k + 1] - r.phase_si[k]) / (1.0 / r.rate_hz);
    rates.push_back(std::move(rate));
  }
  for (const auto& r : rates) spans.emplace_back(r);
  redundant::FusionOptions fusion;
  fusion.detect = true;
  const auto fused = redundant::fuse_records(analysis, spans, 100.0, fusion);
  ASSERT_TRUE(fused.detection.has_value());
  auto expected = redundant::report_json(analysis, parse_unit("deg/s"), &*fused.detection);
  auto actual = doc["redundant"];
  ASSERT_TRUE(actual.contains("fused_curves"));
  actual.erase("fused_curves");
  EXPECT_EQ(actual, expected);
  // Clean records: no fault (false alarms are configured at 0.01 per hour).
  EXPECT_TRUE(doc["redundant"]["faults"].empty()) << doc["redundant"]["faults"];
  EXPECT_GT(doc["redundant"]["tests"].get<int>(), 1000);
  // The fused axes measured from the samples: at tau ~ 1 s (white noise, thousands of degrees
  // of freedom: the bars are ~2 %) each axis agrees with the fused noise the module predicts,
  // 0.866 N / sqrt(tau) on the tetrahedron, within 4 bars.
  for (const auto& curve : doc["redundant"]["fused_curves"]) {
    for (const auto& p : curve["points"]) {
      if (std::abs(p["tau_s"].get<double>() - 1.28) > 0.01) continue;
      const double predicted = 0.8660 * 8.8e-4 / std::sqrt(p["tau_s"].get<double>());
      const double half_bar = 0.5 * (p["ci_high"].get<double>() - p["ci_low"].get<double>());
      EXPECT_NEAR(p["dev"].get<double>(), predicted, 4 * half_bar) << curve["estimator"];
    }
  }
  // The fused axes' figure right before the navigation figures (latitude, path, longitude, budget).
  EXPECT_EQ(doc["figures"][doc["figures"].size() - 5]["id"], "adev_fused");
}

// A step of 0.05 deg/s on gyro 2 at 900 s (57 times the 1 s window's noise of one sensor):
// the study's detector finds it on the recorded data within two windows of its onset; the
// tetrahedron detects a single fault but cannot isolate it.
TEST(Study, RedundantUnitDetectsAStepFaultInTheRecords) {
  std::vector<study::Record> records;
  for (int i = 0; i < 4; ++i) {
    records.push_back(simulated_gyro("g" + std::to_string(i + 1), 8.8e-4, 1e-5, 100.0, 1800.0,
                                     static_cast<std::uint64_t>(31 + i)));
  }
  const double step_rad_s = 0.05 * 3.14159265358979323846 / 180.0;
  const double onset_s = 900.0;
  auto& phase = records[1].phase_si;
  for (std::size_t k = 0; k < phase.size(); ++k) {
    const double t_s = static_cast<double>(k) / 100.0;
    if (t_s > onset_s) phase[k] += step_rad_s * (t_s - onset_s);
  }
  study::StudyOptions o;
  o.geometry = "tetra";
  const auto doc = study::study_json(study::run_study(std::move(records), o));
  const auto& faults = doc["redundant"]["faults"];
  ASSERT_EQ(faults.size(), 1u) << faults;
  // Not isolable: the tetrahedron's one parity vector weighs every sensor alike, so all four are
  // candidates (which one `sensor` names is set by rounding) and the report accuses none.
  EXPECT_EQ(faults[0]["candidates"], nlohmann::json({1, 2, 3, 4})) << faults[0];
  EXPECT_NEAR(faults[0]["t_s"].get<double>(), onset_s, 2.0);
  EXPECT_FALSE(faults[0]["isolated"].get<bool>());
  EXPECT_NE(study::render_markdown(doc).find("on one of sensors 1, 2, 3, 4 from"), std::string::npos);
}

TEST(Study, FiguresCarryDataAndUnits) {
  const auto doc = study::study_json(study::run_study(two_gyros(), options_with_spec()));
  const auto& figures = doc["figures"];
  // Both gyros overlaid, one per gyro, then the navigation error of the first (Figures 5-7)
  // and its error budget.
  std::vector<std::string> ids;
  for (const auto& f : figures) ids.push_back(f["id"]);
  EXPECT_EQ(ids, (std::vector<std::string>{"adev_all_gyros", "adev_gx", "adev_gy", "nav_latitude",
                                           "nav_path", "nav_longitude", "nav_budget"}));
  // The budget is stacked: its top line is 100 % at every time, and the caption names the
  // largest term.
  const auto& budget = figures.back();
  for (const auto& y : budget["series"].back()["y"]) EXPECT_NEAR(y.get<double>(), 100.0, 1e-9);
  EXPECT_NE(budget["caption"].get<std::string>().find("improve it first"), std::string::npos);
  for (const auto& f : figures) {
    const bool adev = f["id"].get<std::string>().rfind("adev", 0) == 0;
    EXPECT_NE(f["y_label"].get<std::string>().find(adev ? "[deg/s]" : "["), std::string::npos);
    EXPECT_NE(f["x_label"].get<std::string>().find(adev ? "[s]" : "[min]"), std::string::npos);
    for (const auto& s : f["series"]) {
      // Every curve has many points; the paper's published 1-hour value is one point.
      EXPECT_GE(s["x"].size(), s["name"] == "paper, published" ? 1u : 3u) << f["id"] << " " << s["name"];
      EXPECT_EQ(s["x"].size(), s["y"].size());
    }
  }
  // Datasheet limits drawn: the tg100 N limit 0.05 deg/sqrt(h) at tau = 1 s.
  bool limit = false;
  for (const auto& s : figures[1]["series"]) {
    if (s["style"] != "limit" || s["name"].get<std::string>().find("datasheet N") == std::string::npos) continue;
    limit = true;
    const double tau0 = s["x"][0], y0 = s["y"][0];
    EXPECT_NEAR(y0 * std::sqrt(tau0), 0.05 / 60.0, 1e-12);
  }
  EXPECT_TRUE(limit);
}

TEST(Study, RefusesChannelsThatCannotBeStudiedTogether) {
  auto a = simulated_gyro("a", 1e-3, 0, 100.0, 60.0, 1);
  auto b = simulated_gyro("b", 1e-3, 0, 200.0, 60.0, 2);
  try {
    study::check_compatible({a, b});
    FAIL() << "mismatched rates accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("200 Hz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fix"), std::string::npos) << e.what();
  }
  auto c = simulated_gyro("c", 1e-3, 0, 100.0, 60.0, 3, "rad/s");
  try {
    study::check_compatible({a, c});
    FAIL() << "mismatched units accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rad/s"), std::string::npos) << e.what();
  }
  auto d = a;
  d.unit_given = false;
  d.name = "d";
  EXPECT_THROW(study::check_compatible({a, d}), InputError);
}

TEST(Study, KeepGoingStudiesTheOtherChannels) {
  auto records = two_gyros();
  study::Record flat = records[0];
  flat.name = "flat";
  for (std::size_t i = 0; i < flat.phase_si.size(); ++i) flat.phase_si[i] = 1e-3 * static_cast<double>(i);  // constant rate
  records.push_back(flat);
  EXPECT_THROW(study::run_study(records, {}), InputError);
  study::StudyOptions o;
  o.keep_going = true;
  const auto result = study::run_study(records, o, {{"broken.csv", "broken.csv:3: bad cell"}});
  ASSERT_EQ(result.channels.size(), 3u);
  EXPECT_TRUE(result.channels[0].fit.has_value());
  EXPECT_TRUE(result.channels[1].fit.has_value());
  EXPECT_FALSE(result.channels[2].fit.has_value());
  EXPECT_NE(result.channels[2].error.find("constant"), std::string::npos);
  const auto doc = study::study_json(result);
  EXPECT_EQ(doc["inputs"].back()["status"], "unreadable");
  EXPECT_EQ(doc["inputs"][2]["status"], "failed");
  EXPECT_NE(study::render_markdown(doc).find("broken.csv"), std::string::npos);
}

TEST(StudyWrite, WritesEveryOutputAndNeverReplacesWithoutForce) {
  ScratchDir scratch;
  const auto doc = study::study_json(study::run_study(two_gyros(), options_with_spec()));
  const auto dir = (scratch.path / "report").string();
  const auto written = study::write_report(doc, dir);
  for (const char* name : {"report.json", "report.html", "report.md", "curves.csv",
                           "coefficients.csv", "spec_comparison.csv", "imu.yaml"}) {
    EXPECT_TRUE(fs::exists(fs::path(dir) / name)) << name;
  }
  // report.json is the document itself.
  EXPECT_EQ(nlohmann::json::parse(slurp(fs::path(dir) / "report.json")), doc);
  // Every figure as SVG and PNG.
  for (const auto& f : doc["figures"]) {
    const auto stem = study::file_stem(f["id"]);
    const auto svg = slurp(fs::path(dir) / "figures" / (stem + ".svg"));
    EXPECT_NE(svg.find("<svg"), std::string::npos) << stem;
    const auto png = slurp(fs::path(dir) / "figures" / (stem + ".png"));
    ASSERT_GT(png.size(), 8u) << stem;
    EXPECT_EQ(png.substr(1, 3), "PNG") << stem;
  }
  // Kalibr: the rule combining the axes is stated; N is the larger of the two gyros' N.
  const auto yaml = slurp(fs::path(dir) / "imu.yaml");
  EXPECT_NE(yaml.find("# rule: each key holds the largest"), std::string::npos);
  // A second run refuses, and leaves the report untouched; --force replaces it.
  const auto before = slurp(fs::path(dir) / "report.md");
  std::ofstream(fs::path(dir) / "report.md") << "mine";
  try {
    study::write_report(doc, dir);
    FAIL() << "existing report replaced without force";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--force"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(fs::path(dir) / "report.md"), "mine");
  study::write_report(doc, dir, {true, "", "gnuplot"});
  EXPECT_EQ(slurp(fs::path(dir) / "report.md"), before);
  // No staging left behind.
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename().string().find(".imunoise-staging"), std::string::npos);
  }
}

TEST(StudyWrite, UnwritableDirectoryIsAnInputError) {
  ScratchDir scratch;
  const auto doc = study::study_json(study::run_study(two_gyros(), {}));
  std::ofstream(scratch.path / "plain-file") << "x";
  EXPECT_THROW(study::write_report(doc, (scratch.path / "plain-file").string()), InputError);
  EXPECT_THROW(study::write_report(doc, (scratch.path / "plain-file" / "sub").string()), InputError);
  if (::geteuid() != 0) {  // root writes anywhere: the permission case needs a normal user
    const auto ro = scratch.path / "read-only";
    fs::create_directories(ro);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(study::write_report(doc, ro.string()), InputError);
    fs::permissions(ro, fs::perms::owner_all);
  }
}

}  // namespace
}  // namespace imunoise

namespace imunoise {
namespace {

TEST(Study, KalibrFileCombinesTheAxesByTheStatedRule) {
  auto records = two_gyros();
  records.push_back(test::simulated_gyro("ax", 5e-4, 0.0, 100.0, 1800.0, 41, "g"));
  const auto result = study::run_study(std::move(records), {});
  const auto doc = study::study_json(result);
  const auto& k = doc["kalibr"];
  ASSERT_TRUE(k["written"].get<bool>());
  EXPECT_TRUE(k["complete"].get<bool>());
  EXPECT_EQ(k["gyro_axes"], (nlohmann::json{"gx", "gy"}));
  EXPECT_EQ(k["accelerometer_axes"], (nlohmann::json{"ax"}));
  // gyroscope_noise_density is the larger of the two gyros' N (rad/s/sqrt(Hz) = rad/sqrt(s)).
  const double n = std::max(result.channels[0].fit->coefficients.random_walk.value,
                            result.channels[1].fit->coefficients.random_walk.value);
  const std::string text = k["text"];
  const auto at = text.find("\ngyroscope_noise_density: ");
  ASSERT_NE(at, std::string::npos) << text;
  EXPECT_DOUBLE_EQ(std::stod(text.substr(at + 26)), n);
  EXPECT_NE(text.find("\naccelerometer_noise_density: "), std::string::npos) << text;
}

// The whole IMU: gyros and accelerometers on their axes by name (here given out of order), the
// physical models only, each sensor's fitted coefficients on its own axis; a study without
// accelerometers has none.
TEST(Study, WholeImuNavigationPutsEachChannelOnItsAxis) {
  std::vector<study::Record> records;
  records.push_back(test::simulated_gyro("gyro_y", 2e-3, 0.0, 100.0, 1200.0, 51));
  records.push_back(test::simulated_gyro("gyro_x", 1e-3, 0.0, 100.0, 1200.0, 52));
  records.push_back(test::simulated_gyro("accel_x", 1e-3, 0.0, 100.0, 1200.0, 53, "g"));
  const auto result = study::run_study(records, {});
  ASSERT_TRUE(result.imu.has_value());
  EXPECT_EQ(result.imu->gyro_channels, (std::array<std::string, 3>{"gyro_x", "gyro_y", ""}));
  EXPECT_EQ(result.imu->accel_channels, (std::array<std::string, 3>{"accel_x", "", ""}));
  const auto& nav = result.imu->result;
  EXPECT_EQ(nav.terms[1].n_rad_sqrt_s, result.channels[0].fit->coefficients.random_walk.value);
  EXPECT_EQ(nav.terms[0].n_rad_sqrt_s, result.channels[1].fit->coefficients.random_walk.value);
  EXPECT_EQ(nav.accel_terms[0].n_m_s_sqrt_s, result.channels[2].fit->coefficients.random_walk.value);
  EXPECT_EQ(nav.terms[2].n_rad_sqrt_s, 0.0);
  for (const auto& m : nav.models) EXPECT_NE(m.model, nav::Model::paper);
  const auto doc = study::study_json(result);
  EXPECT_EQ(doc["imu_nav"]["accel_channels"][0], "accel_x");
  records.pop_back();
  EXPECT_FALSE(study::run_study(records, {}).imu.has_value());
}

}  // namespace
}  // namespace imunoise

namespace imunoise {
namespace {

// A gyro at 100 Hz, 1200 s, white rate noise of 0.01 deg/s whose level grows by `step` at
// `step_at_s`, with its dynamic Allan variance (windows of 60 s every 10 s) as --davar makes it.
study::Record davar_gyro(const std::string& name, double step, double step_at_s, std::uint64_t seed,
                         preprocess::DavarResult* davar) {
  const double rate = 100.0;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<double> y(120'000);
  const double deg = parse_unit("deg/s").to_si;
  for (std::size_t i = 0; i < y.size(); ++i) {
    y[i] = 0.01 * deg * normal(rng) * (static_cast<double>(i) / rate >= step_at_s ? step : 1.0);
  }
  *davar = preprocess::dynamic_allan(y, rate, {60.0, 10.0});
  study::Record r;
  r.name = name;
  r.source = name + ".csv";
  r.rate_hz = rate;
  r.n_samples = y.size();
  r.phase_si = phase_from_rate(y, 1.0 / rate, compensated_mean(y));
  r.rate_unit = parse_unit("deg/s");
  r.unit_given = true;
  r.davar = *davar;
  return r;
}

// The report's DAVAR: the module's result in the record's unit, its verdict, a heat map with
// one cell per window and tau and a cross on each flagged cell, and a sentence in report.md. A
// step in noise level (1.5x at 400 s) is found near 400 s; a stationary gyro is called so.
TEST(StudyDavar, HeatMapAndVerdictInTheReport) {
  preprocess::DavarResult step_davar, flat_davar;
  std::vector<study::Record> records{davar_gyro("stepped", 1.5, 400.0, 41, &step_davar),
                                     davar_gyro("steady", 1.0, 1e9, 42, &flat_davar)};
  ASSERT_FALSE(step_davar.stationary);
  ASSERT_TRUE(flat_davar.stationary);
  const auto doc = study::study_json(study::run_study(std::move(records), {}));
  const auto& d = doc["channels"][0]["davar"];
  ASSERT_TRUE(d.is_object());
  const double deg = parse_unit("deg/s").to_si;
  std::size_t cells = 0, flagged = 0;
  for (std::size_t w = 0; w < step_davar.avar.size(); ++w) {
    for (std::size_t j = 0; j < step_davar.tau_s.size(); ++j) {
      if (!(step_davar.avar[w][j] > 0.0)) continue;
      ++cells;
      flagged += step_davar.flagged[w][j] ? 1 : 0;
      EXPECT_NEAR(d["adev"][w][j].get<double>(), std::sqrt(step_davar.avar[w][j]) / deg,
                  1e-12 * d["adev"][w][j].get<double>());
    }
  }
  EXPECT_GT(flagged, 0u);
  EXPECT_FALSE(d["stationary"].get<bool>());
  EXPECT_EQ(d["unit"], "deg/s");
  ASSERT_EQ(d["change_times_s"].size(), 1u);
  EXPECT_NEAR(d["change_times_s"][0].get<double>(), 400.0, 30.0);  // half a window
  EXPECT_TRUE(doc["channels"][1]["davar"]["stationary"].get<bool>());
  const nlohmann::json* heat = nullptr;
  for (const auto& f : doc["figures"]) {
    if (f["id"] == "davar_stepped") heat = &f;
  }
  ASSERT_NE(heat, nullptr);
  EXPECT_EQ((*heat)["title"], "Dynamic Allan deviation of stepped: not stationary");
  const auto& map = (*heat)["series"][0];
  EXPECT_EQ(map["style"], "heatmap");
  EXPECT_EQ(map["z"].size(), cells);
  EXPECT_EQ((*heat)["series"][1]["x"].size(), flagged);
  // The cells tile time and tau: each cell spans one step around its window's centre and an
  // octave around its tau.
  EXPECT_NEAR(map["x_high"][0].get<double>() - map["x_low"][0].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(map["y_high"][0].get<double>() / map["y_low"][0].get<double>(), 2.0, 1e-12);
  const std::string md = study::render_markdown(doc);
  EXPECT_NE(md.find("## Stationarity (dynamic Allan variance)"), std::string::npos);
  EXPECT_NE(md.find("stepped: " + std::to_string(step_davar.avar.size()) + " windows of 60 s every 10 s"),
            std::string::npos) << md;
  EXPECT_NE(md.find("NOT stationary"), std::string::npos);
  EXPECT_NE(md.find("steady: "), std::string::npos);
  EXPECT_NE(md.find("; stationary (0 windows outside"), std::string::npos) << md;
  EXPECT_NE(study::render_html(doc, "").find("Stationarity (dynamic Allan variance)"), std::string::npos);
  // gnuplot draws the heat map as coloured boxes on a log colour axis.
  const std::string gp = study::gnuplot_script(*heat, "a.svg", "a.png");
  EXPECT_NE(gp.find("with boxxyerror fs solid 1.0 noborder fc palette"), std::string::npos);
  EXPECT_NE(gp.find("set logscale cb"), std::string::npos);
}

}  // namespace
}  // namespace imunoise
