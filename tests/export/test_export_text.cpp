// The texts of the filter exports: each value read back (as its consumer reads it) equals the
// model value in the consumer's units and discretisation, the header says what was measured,
// with the intervals and the inflation, absent terms are placeholders the consumer does not
// read as numbers, and the registry parses targets and refuses to overwrite.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "consumer_readers.hpp"
#include "export_fixtures.hpp"
#include "imunoise/error.hpp"
#include "imunoise/export/export_target.hpp"
#include "imunoise/export/gtsam.hpp"
#include "imunoise/export/kalibr.hpp"
#include "imunoise/export/matlab.hpp"
#include "imunoise/export/openvins.hpp"
#include "imunoise/export/orbslam3.hpp"
#include "imunoise/export/px4.hpp"
#include "imunoise/export/ros.hpp"
#include "imunoise/export/vins.hpp"

namespace imunoise::exports::test {
namespace {

const double kS = std::sqrt(kRateHz);

void expect_values(const FileValues& v, double gw, double gk, double aw, double ak, const char* what) {
  ASSERT_TRUE(v.gyro_white && v.gyro_walk && v.accel_white && v.accel_walk) << what;
  EXPECT_EQ(*v.gyro_white, gw) << what;
  EXPECT_EQ(*v.gyro_walk, gk) << what;
  EXPECT_EQ(*v.accel_white, aw) << what;
  EXPECT_EQ(*v.accel_walk, ak) << what;
}

// Values are written so that they read back to the same double (round_trip_number).
TEST(ExportText, EachConsumerReadsItsUnitsAndDiscretisation) {
  const auto m = model(true, 1.5);
  const double f = 1.5;
  expect_values(read_kalibr(kalibr_yaml(m)), kGyroN * f, kGyroK * f, kAccelN * f, kAccelK * f, "kalibr");
  expect_values(read_openvins(openvins_yaml(m)), kGyroN * f, kGyroK * f, kAccelN * f, kAccelK * f, "openvins");
  expect_values(read_orbslam3(orbslam3_yaml(m)), kGyroN * f, kGyroK * f, kAccelN * f, kAccelK * f, "orbslam3");
  expect_values(read_matlab(matlab_script(m)), kGyroN * f, kGyroK * f, kAccelN * f, kAccelK * f, "matlab");
  expect_values(read_vins(vins_yaml(m)), kGyroN * kS * f, kGyroK * kS * f, kAccelN * kS * f, kAccelK * kS * f,
                "vins");
  const double se = std::sqrt(100.0);
  expect_values(read_px4(px4_params(m)), kGyroN * se * f, kGyroK * se * f, kAccelN * se * f, kAccelK * se * f,
                "px4");
  const auto sq = [](double x) { return x * x; };
  expect_values(read_gtsam(gtsam_json(m).dump()), sq(kGyroN * f), sq(kGyroK * f), sq(kAccelN * f), sq(kAccelK * f),
                "gtsam");
  const auto ros = read_ros(ros_covariance_yaml(m));
  EXPECT_EQ(*ros.gyro_white, sq(kGyroN * kS * f));
  EXPECT_EQ(*ros.accel_white, sq(kAccelN * kS * f));
  // Rates where the consumer takes one from the file.
  EXPECT_EQ(*read_kalibr(kalibr_yaml(m)).rate_hz, kRateHz);
  EXPECT_EQ(*read_openvins(openvins_yaml(m)).rate_hz, kRateHz);
  EXPECT_EQ(*read_orbslam3(orbslam3_yaml(m)).rate_hz, kRateHz);
}

TEST(ExportText, EveryFileSaysWhatWasMeasuredAndTheInflation) {
  for (double inflation : {1.0, 2.0}) {
    const auto m = model(true, inflation);
    for (auto t : all_targets()) {
      for (const auto& file : render_target({t, ""}, m, "")) {
        const std::string& text = file.text;
        const std::string name(target_name(t));
        EXPECT_NE(text.find("bench.bag"), std::string::npos) << name;
        if (t == Target::gtsam && file.path.ends_with(".json")) {
          const auto j = nlohmann::json::parse(text);
          EXPECT_EQ(j["measured"]["inflation"].get<double>(), inflation);
          EXPECT_EQ(j["measured"]["gyroscope"]["N"]["ci_low"].get<double>(), 0.9 * kGyroN);
          EXPECT_EQ(j["measured"]["accelerometer"]["channels"], "accel_x accel_y accel_z");
          continue;
        }
        EXPECT_NE(text.find("inflation factor: " + std::string(inflation == 1.0 ? "1.0" : "2.0")), std::string::npos)
            << name;
        EXPECT_NE(text.find("gyro_x gyro_y gyro_z (per term the largest of 3 axes)"), std::string::npos) << name;
        EXPECT_NE(text.find("accel_x accel_y accel_z"), std::string::npos) << name;
        EXPECT_NE(text.find("200.0 Hz"), std::string::npos) << name;
        EXPECT_NE(text.find("95% interval 0.00018 .. 0.00022"), std::string::npos) << name << "\n" << text;
        EXPECT_EQ(text.find("<FILL IN>"), std::string::npos) << name;
      }
    }
  }
}

// Each written value carries its own interval, in the file's units and discretisation.
TEST(ExportText, EachValueStatesItsInterval) {
  const auto m = model(true, 2.0);
  char want[128];
  std::snprintf(want, sizeof want, "(95%% interval %.6g .. %.6g)", 0.9 * kGyroN * kS * 2.0, 1.1 * kGyroN * kS * 2.0);
  const std::string vins = vins_yaml(m);
  ASSERT_NE(vins.find("gyr_n: "), std::string::npos);
  EXPECT_NE(vins.substr(vins.find("gyr_n: ")).find(want), std::string::npos) << want << "\n" << vins;
  const auto sq = [](double x) { return x * x; };
  std::snprintf(want, sizeof want, "(95%% interval %.6g .. %.6g)", sq(0.9 * kAccelN * kS * 2.0),
                sq(1.1 * kAccelN * kS * 2.0));
  const std::string ros = ros_covariance_yaml(m);
  EXPECT_NE(ros.substr(ros.find("linear_acceleration_covariance: [")).find(want), std::string::npos) << want;
  for (const auto& text : {openvins_yaml(m), orbslam3_yaml(m), px4_params(m), matlab_script(m), gtsam_python(m)}) {
    EXPECT_NE(text.find("95% interval"), std::string::npos);
  }
}

// Without an accelerometer (a gyro fit), no accelerometer number is invented: the consumer
// finds no value, and the file says why.
TEST(ExportText, AbsentTermsArePlaceholdersNotNumbers) {
  const auto m = model(false);
  const std::pair<const char*, FileValues> read[] = {
      {"kalibr", read_kalibr(kalibr_yaml(m))},     {"openvins", read_openvins(openvins_yaml(m))},
      {"vins", read_vins(vins_yaml(m))},           {"orbslam3", read_orbslam3(orbslam3_yaml(m))},
      {"gtsam", read_gtsam(gtsam_json(m).dump())}, {"px4", read_px4(px4_params(m))},
      {"matlab", read_matlab(matlab_script(m))},   {"ros", read_ros(ros_covariance_yaml(m))},
  };
  for (const auto& [name, v] : read) {
    EXPECT_TRUE(v.gyro_white) << name;
    EXPECT_FALSE(v.accel_white) << name;
    EXPECT_FALSE(v.accel_walk) << name;
  }
  for (const auto& text : {openvins_yaml(m), vins_yaml(m), orbslam3_yaml(m), px4_params(m), matlab_script(m),
                           ros_covariance_yaml(m), gtsam_python(m)}) {
    EXPECT_NE(text.find("NOT MEASURED"), std::string::npos) << text;
  }
  EXPECT_NE(vins_yaml(m).find("VINS reads a missing key as 0 WITHOUT a warning"), std::string::npos);
  EXPECT_EQ(gtsam_json(m)["notes"]["biasAccCovariance"].get<std::string>().rfind("NOT MEASURED", 0), 0u);

  // An unidentified walk is absent too, with the fit's reason.
  auto no_k = model();
  no_k.gyro->coefficients.rate_random_walk = Coefficient{};
  no_k.gyro->coefficients.rate_random_walk.note = "record too short";
  EXPECT_FALSE(read_orbslam3(orbslam3_yaml(no_k)).gyro_walk);
  EXPECT_NE(orbslam3_yaml(no_k).find("K not identified (record too short)"), std::string::npos);

  // Kalibr and OpenVINS files are gyro files first: an accelerometer alone is refused.
  auto accel_only = model();
  accel_only.gyro.reset();
  EXPECT_THROW(kalibr_yaml(accel_only), InputError);
  EXPECT_THROW(openvins_yaml(accel_only), InputError);
  EXPECT_FALSE(read_vins(vins_yaml(accel_only)).gyro_white);
  auto nothing = accel_only;
  nothing.accel.reset();
  EXPECT_THROW(vins_yaml(nothing), InputError);
  auto zero_rate = model();
  zero_rate.rate_hz = 0.0;
  EXPECT_THROW(ros_covariance_yaml(zero_rate), InputError);
}

TEST(ExportText, PythonSnippetBuildsTheParams) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  const auto dir = std::filesystem::temp_directory_path() / ("imunoise-gtsam-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // A stand-in gtsam module recording the setters (GTSAM itself is not a Debian package here).
  std::ofstream(dir / "gtsam.py") << "import json\n"
                                     "calls = {}\n"
                                     "class PreintegrationCombinedParams:\n"
                                     "    @staticmethod\n"
                                     "    def MakeSharedU(g):\n"
                                     "        return PreintegrationCombinedParams()\n"
                                     "    def __getattr__(self, name):\n"
                                     "        return lambda m: calls.__setitem__(name, float(m[1][1]))\n";
  std::ofstream(dir / "snippet.py") << gtsam_python(model());
  std::ofstream(dir / "run.py") << "import runpy, json, gtsam\nrunpy.run_path('snippet.py')\n"
                                   "print(json.dumps(gtsam.calls))\n";
  const std::string out = (dir / "out.json").string();
  const std::string cmd = "cd " + dir.string() + " && /usr/bin/python3 run.py > " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(out);
  const auto calls = nlohmann::json::parse(in);
  EXPECT_EQ(calls["setGyroscopeCovariance"].get<double>(), kGyroN * kGyroN);
  EXPECT_EQ(calls["setBiasAccCovariance"].get<double>(), kAccelK * kAccelK);
  // Kalibr reads imu.yaml with PyYAML (YAML 1.1): every value must come back a float, not a
  // string ("3e-05") or an int ("200"); ROS tools read the covariance file the same way.
  std::ofstream(dir / "kalibr.yaml") << kalibr_yaml(model());
  std::ofstream(dir / "ros.yaml") << ros_covariance_yaml(model());
  std::ofstream(dir / "yaml_types.py")
      << "import yaml\n"
         "k = yaml.safe_load(open('kalibr.yaml'))\n"
         "for key in ('gyroscope_noise_density', 'gyroscope_random_walk', 'accelerometer_noise_density',\n"
         "            'accelerometer_random_walk', 'update_rate'):\n"
         "    assert type(k[key]) is float, (key, k[key])\n"
         "assert k['gyroscope_noise_density'] == 0.0002 and k['update_rate'] == 200.0\n"
         "r = yaml.safe_load(open('ros.yaml'))\n"
         "assert all(type(v) is float for v in r['angular_velocity_covariance'])\n";
  EXPECT_EQ(std::system(("cd " + dir.string() + " && /usr/bin/python3 yaml_types.py").c_str()), 0);
  // Without an accelerometer the snippet stops instead of running with made-up values.
  std::ofstream(dir / "snippet.py") << gtsam_python(model(false));
  EXPECT_NE(std::system((cmd + " 2>/dev/null").c_str()), 0);
  std::filesystem::remove_all(dir);
}

TEST(ExportTargets, NamesFilesAndRefusals) {
  EXPECT_EQ(target_list(), "kalibr openvins vins orbslam3 gtsam px4 matlab ros");
  EXPECT_EQ(parse_target("orbslam3"), Target::orbslam3);
  try {
    parse_target("rovio");
    ADD_FAILURE() << "no throw";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown target 'rovio'; targets: kalibr openvins vins orbslam3 gtsam px4 matlab ros");
  }
  EXPECT_EQ(parse_export_spec("px4:out/x.params").path, "out/x.params");
  EXPECT_EQ(parse_export_spec("ros").path, "");
  EXPECT_THROW(parse_export_spec("px4:"), InputError);
  EXPECT_THROW(parse_export_spec("px4:-"), InputError);
  EXPECT_EQ(target_paths({Target::gtsam, ""}, "rep"), (std::vector<std::string>{"rep/gtsam_imu.json", "rep/gtsam_imu.py"}));
  EXPECT_EQ(target_paths({Target::openvins, ""}, ""), std::vector<std::string>{"kalibr_imu_chain.yaml"});
  EXPECT_THROW(target_paths({Target::gtsam, "params.py"}, ""), InputError);

  const auto dir = std::filesystem::temp_directory_path() / ("imunoise-targets-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::vector<ExportSpec> specs{{Target::vins, ""}, {Target::px4, (dir / "p.params").string()}};
  const auto written = write_targets(specs, model(), dir.string(), false);
  EXPECT_EQ(written.size(), 2u);
  EXPECT_TRUE(std::filesystem::exists(dir / "vins_imu.yaml"));
  // Existing files are kept without force; with one refused, none is written.
  const std::vector<ExportSpec> again{{Target::ros, ""}, {Target::vins, ""}};
  EXPECT_THROW(write_targets(again, model(), dir.string(), false), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "ros_imu_covariance.yaml"));
  EXPECT_NO_THROW(write_targets(again, model(), dir.string(), true));
  const std::vector<ExportSpec> twice{{Target::vins, ""}, {Target::orbslam3, (dir / "vins_imu.yaml").string()}};
  EXPECT_THROW(write_targets(twice, model(), dir.string(), true), InputError);
  std::filesystem::remove_all(dir);
}

TEST(ExportModel, TriadTakesTheLargestAxisPerTerm) {
  std::vector<AxisFit> fits;
  for (int i = 0; i < 3; ++i) {
    AxisFit a{"g" + std::to_string(i), {}};
    a.coefficients.random_walk = known(1e-4 * (i + 1));
    a.coefficients.rate_random_walk = known(1e-5 * (3 - i));
    fits.push_back(a);
  }
  AxisFit accel{"a0", {}};
  accel.coefficients.quantity = Quantity::acceleration;
  accel.coefficients.random_walk = known(1e-3);
  fits.push_back(accel);
  AxisFit temperature{"t", {}};
  temperature.coefficients.quantity = Quantity::dimensionless;
  fits.push_back(temperature);
  const auto m = make_export_model(fits, 100.0, 1.0, "f.csv");
  ASSERT_TRUE(m.gyro && m.accel);
  EXPECT_EQ(m.gyro->coefficients.random_walk.value, 1e-4 * 3);
  EXPECT_EQ(m.gyro->coefficients.rate_random_walk.value, 1e-5 * 3);
  EXPECT_EQ(m.gyro->channels, "g0 g1 g2");
  EXPECT_EQ(m.accel->selection, "one axis");
  EXPECT_THROW(make_export_model(std::span(fits).subspan(4), 100.0, 1.0, "f.csv"), InputError);
  EXPECT_THROW(make_export_model(fits, 100.0, 0.0, "f.csv"), InputError);
}

}  // namespace
}  // namespace imunoise::exports::test
