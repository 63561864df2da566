#pragma once
// Each export read back the way its consumer reads it: cv::FileStorage for the OpenCV-dialect
// YAML (OpenVINS, VINS-Fusion, ORB-SLAM3 all parse their configuration with it), yaml-cpp for
// Kalibr's and ROS's plain YAML, nlohmann for the GTSAM JSON, and small strict parsers for
// QGroundControl's .params lines and the MATLAB property assignments. A reader fails the
// test (ADD_FAILURE + nullopt) on anything it does not understand.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <map>
#include <optional>
#include <opencv2/core/persistence.hpp>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace imunoise::exports::test {

/// The four numbers a filter takes, as written in the file (its own units and meaning).
struct FileValues {
  std::optional<double> gyro_white, gyro_walk, accel_white, accel_walk;
  std::optional<double> rate_hz;  ///< the rate written in the file, when it has one
};

inline std::optional<double> strict_number(const std::string& text) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

inline std::optional<double> cv_real(const cv::FileNode& node) {
  if (node.empty()) return std::nullopt;
  EXPECT_TRUE(node.isReal()) << node.name() << " is not a real number for OpenCV";
  return node.real();
}

inline FileValues read_openvins(const std::string& text) {
  cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_TRUE(fs.isOpened());
  const cv::FileNode imu = fs["imu0"];
  EXPECT_TRUE(imu.isMap());
  cv::FileNode tib = imu["T_i_b"];
  EXPECT_EQ(tib.size(), 4u);
  EXPECT_EQ(static_cast<std::string>(imu["rostopic"]), "/imu0");
  EXPECT_EQ(static_cast<double>(imu["time_offset"]), 0.0);
  EXPECT_EQ(static_cast<std::string>(imu["model"]), "kalibr");
  return {cv_real(imu["gyroscope_noise_density"]), cv_real(imu["gyroscope_random_walk"]),
          cv_real(imu["accelerometer_noise_density"]), cv_real(imu["accelerometer_random_walk"]),
          cv_real(imu["update_rate"])};
}

inline FileValues read_vins(const std::string& text) {
  cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_TRUE(fs.isOpened());
  return {cv_real(fs["gyr_n"]), cv_real(fs["gyr_w"]), cv_real(fs["acc_n"]), cv_real(fs["acc_w"]), std::nullopt};
}

inline FileValues read_orbslam3(const std::string& text) {
  cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_TRUE(fs.isOpened());
  return {cv_real(fs["IMU.NoiseGyro"]), cv_real(fs["IMU.GyroWalk"]), cv_real(fs["IMU.NoiseAcc"]),
          cv_real(fs["IMU.AccWalk"]), cv_real(fs["IMU.Frequency"])};
}

inline std::optional<double> yaml_real(const YAML::Node& n) {
  if (!n) return std::nullopt;
  return n.as<double>();
}

inline FileValues read_kalibr(const std::string& text) {
  const YAML::Node y = YAML::Load(text);
  EXPECT_EQ(y["rostopic"].as<std::string>(), "/imu0");
  return {yaml_real(y["gyroscope_noise_density"]), yaml_real(y["gyroscope_random_walk"]),
          yaml_real(y["accelerometer_noise_density"]), yaml_real(y["accelerometer_random_walk"]),
          yaml_real(y["update_rate"])};
}

/// ROS: the covariance diagonal (all three equal, off-diagonals zero); walks have no place.
inline FileValues read_ros(const std::string& text) {
  const YAML::Node y = YAML::Load(text);
  const auto diag = [](const YAML::Node& n) -> std::optional<double> {
    if (!n) return std::nullopt;
    EXPECT_EQ(n.size(), 9u);
    for (int i = 0; i < 9; ++i) {
      if (i % 4 != 0) EXPECT_EQ(n[i].as<double>(), 0.0);
    }
    EXPECT_EQ(n[0].as<double>(), n[4].as<double>());
    EXPECT_EQ(n[0].as<double>(), n[8].as<double>());
    return n[0].as<double>();
  };
  return {diag(y["angular_velocity_covariance"]), std::nullopt, diag(y["linear_acceleration_covariance"]),
          std::nullopt, std::nullopt};
}

inline FileValues read_gtsam(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  const auto diag = [&](const char* key) -> std::optional<double> {
    if (j.at(key).is_null()) return std::nullopt;
    const auto& m = j.at(key);
    EXPECT_EQ(m.size(), 3u);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if (r != c) EXPECT_EQ(m[r][c].get<double>(), 0.0);
      }
    }
    EXPECT_EQ(m[0][0].get<double>(), m[2][2].get<double>());
    return m[1][1].get<double>();
  };
  return {diag("gyroscopeCovariance"), diag("biasOmegaCovariance"), diag("accelerometerCovariance"),
          diag("biasAccCovariance"), std::nullopt};
}

/// QGroundControl .params: '#' lines are comments, every other line is exactly
/// vehicle<TAB>component<TAB>name<TAB>value<TAB>type with type 9 (float).
inline std::map<std::string, double> parse_params(const std::string& text) {
  std::map<std::string, double> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::size_t start = 0;
    for (std::size_t tab; (tab = line.find('\t', start)) != std::string::npos; start = tab + 1) {
      f.push_back(line.substr(start, tab - start));
    }
    f.push_back(line.substr(start));
    if (f.size() != 5 || f[0] != "1" || f[1] != "1" || f[4] != "9") {
      ADD_FAILURE() << "line " << number << " is not a .params line: " << line;
      continue;
    }
    const auto v = strict_number(f[3]);
    if (!v) {
      ADD_FAILURE() << "line " << number << ": value '" << f[3] << "' is not a number";
      continue;
    }
    if (!out.emplace(f[2], *v).second) ADD_FAILURE() << "line " << number << ": " << f[2] << " twice";
  }
  return out;
}

inline FileValues read_px4(const std::string& text) {
  const auto p = parse_params(text);
  const auto get = [&](const char* k) -> std::optional<double> {
    const auto it = p.find(k);
    return it == p.end() ? std::nullopt : std::optional<double>(it->second);
  };
  return {get("EKF2_GYR_NOISE"), get("EKF2_GYR_B_NOISE"), get("EKF2_ACC_NOISE"), get("EKF2_ACC_B_NOISE"),
          std::nullopt};
}

/// MATLAB: every line that is not a comment is "var = gyroparams;", "var = accelparams;" or
/// "var.Property = value;" (optionally followed by a % comment); values are numbers or
/// "double-sided".
inline std::map<std::string, std::string> parse_matlab(const std::string& text) {
  std::map<std::string, std::string> out;
  const std::regex ctor(R"(^(gyro|accel) = (gyroparams|accelparams);$)");
  const std::regex assign(R"(^(gyro|accel)\.([A-Za-z]+) = ([^;%]+);(  %.*)?$)");
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '%') continue;
    std::smatch m;
    if (std::regex_match(line, m, ctor)) {
      EXPECT_EQ(m[1].str() + "params", m[2].str());
      continue;
    }
    if (!std::regex_match(line, m, assign)) {
      ADD_FAILURE() << "not a MATLAB assignment imunoise writes: " << line;
      continue;
    }
    out[m[1].str() + "." + m[2].str()] = m[3].str();
  }
  return out;
}

inline FileValues read_matlab(const std::string& text) {
  const auto p = parse_matlab(text);
  const auto get = [&](const char* k) -> std::optional<double> {
    const auto it = p.find(k);
    if (it == p.end()) return std::nullopt;
    const auto v = strict_number(it->second);
    EXPECT_TRUE(v) << k << " = " << it->second;
    return v;
  };
  if (p.contains("gyro.NoiseDensity")) EXPECT_EQ(p.at("gyro.NoiseType"), "\"double-sided\"");
  return {get("gyro.NoiseDensity"), get("gyro.RandomWalk"), get("accel.NoiseDensity"), get("accel.RandomWalk"),
          std::nullopt};
}

}  // namespace imunoise::exports::test
