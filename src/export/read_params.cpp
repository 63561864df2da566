#include "imunoise/export/read_params.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "imunoise/error.hpp"

namespace imunoise::exports {
namespace {

std::optional<double> strict_number(std::string text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  while (!text.empty() && text.front() == ' ') text.erase(text.begin());
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || text.empty()) return std::nullopt;
  return v;
}

[[noreturn]] void bad(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}

// OpenCV writes "%YAML:1.0", which YAML 1.2 readers reject as a directive: drop that line.
YAML::Node load_yaml(const std::string& text, const std::string& name) {
  std::string body = text;
  if (body.rfind("%YAML", 0) == 0) {
    const auto eol = body.find('\n');
    body = eol == std::string::npos ? "" : body.substr(eol + 1);
  }
  try {
    return YAML::Load(body);
  } catch (const YAML::Exception& e) {
    bad(name, fmt::format("not YAML ({}, line {}); fix: check the file or give --target", e.msg, e.mark.line + 1));
  }
}

std::optional<Target> detect(const std::string& text, const std::string& name) {
  const auto ext = std::filesystem::path(name).extension().string();
  if (ext == ".params") return Target::px4;
  if (ext == ".m") return Target::matlab;
  if (ext == ".json") return Target::gtsam;
  YAML::Node y;
  try {
    y = load_yaml(text, name);
  } catch (const InputError&) {
    return std::nullopt;
  }
  if (!y.IsMap()) return std::nullopt;
  if (y["imu0"]) return Target::openvins;
  if (y["IMU.NoiseGyro"] || y["IMU.NoiseAcc"]) return Target::orbslam3;
  if (y["gyr_n"] || y["acc_n"]) return Target::vins;
  if (y["angular_velocity_covariance"] || y["linear_acceleration_covariance"]) return Target::ros;
  if (y["gyroscope_noise_density"] || y["accelerometer_noise_density"]) return Target::kalibr;
  return std::nullopt;
}

double yaml_number(const YAML::Node& n, const std::string& name, const std::string& key) {
  const auto v = n.IsScalar() ? strict_number(n.Scalar()) : std::nullopt;
  if (!v) bad(name, fmt::format("{} is not a number (line {}); fix: write a plain number", key, n.Mark().line + 1));
  return *v;
}

void read_yaml(ParamsFile& f, const std::string& text) {
  const YAML::Node top = load_yaml(text, f.path);
  if (!top.IsMap()) bad(f.path, "not a YAML map of keys; fix: check the file or --target");
  const YAML::Node y = f.target == Target::openvins ? top["imu0"] : top;
  if (!y || !y.IsMap()) bad(f.path, f.target == Target::openvins ? "no imu0 map (OpenVINS)" : "not a YAML map");
  for (const auto& spec : target_keys(f.target)) {
    const YAML::Node n = y[spec.key];
    if (!n) {
      f.missing.push_back(spec.key);
      continue;
    }
    if (f.target == Target::ros) {
      if (!n.IsSequence() || n.size() != 9) bad(f.path, spec.key + " is not a list of 9 numbers (row-major 3x3)");
      const double d = yaml_number(n[0], f.path, spec.key + "[0]");
      if (d == -1.0) {  // the message's own "not provided"
        f.missing.push_back(spec.key);
        continue;
      }
      for (int i : {4, 8}) {
        if (yaml_number(n[i], f.path, fmt::format("{}[{}]", spec.key, i)) != d) {
          bad(f.path, spec.key + ": the diagonal differs between axes; imunoise checks one value per triad");
        }
      }
      f.values.push_back({spec, d});
      continue;
    }
    f.values.push_back({spec, yaml_number(n, f.path, spec.key)});
  }
  for (const char* key : {"update_rate", "IMU.Frequency"}) {
    if (y[key]) f.rate_hz = yaml_number(y[key], f.path, key);
  }
}

void read_json(ParamsFile& f, const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    bad(f.path, std::string("not JSON: ") + e.what());
  }
  for (const auto& spec : target_keys(f.target)) {
    if (!j.contains(spec.key) || j[spec.key].is_null()) {
      f.missing.push_back(spec.key);
      continue;
    }
    const auto& m = j[spec.key];
    if (!m.is_array() || m.size() != 3 || !m[0].is_array() || m[0].size() != 3 || !m[0][0].is_number() ||
        !m[1][1].is_number() || !m[2][2].is_number()) {
      bad(f.path, spec.key + " is not a 3x3 array of numbers");
    }
    const double d = m[0][0].get<double>();
    if (m[1][1].get<double>() != d || m[2][2].get<double>() != d) {
      bad(f.path, spec.key + ": the diagonal differs between axes; imunoise checks one value per triad");
    }
    f.values.push_back({spec, d});
  }
}

void read_lines(ParamsFile& f, const std::string& text) {
  std::map<std::string, double> found;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  const std::regex assign(R"(^\s*((?:gyro|accel)\.[A-Za-z]+)\s*=\s*([^;%]+);?\s*(%.*)?$)");
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (f.target == Target::px4) {
      if (line.empty() || line[0] == '#') continue;
      std::vector<std::string> field;
      std::size_t start = 0;
      for (std::size_t tab; (tab = line.find('\t', start)) != std::string::npos; start = tab + 1) {
        field.push_back(line.substr(start, tab - start));
      }
      field.push_back(line.substr(start));
      if (field.size() != 5) {
        bad(f.path, fmt::format("line {}: not a QGroundControl parameter line (vehicle, component, name, value, "
                                "type separated by tabs)",
                                number));
      }
      const auto v = strict_number(field[3]);
      if (!v) bad(f.path, fmt::format("line {}: {} value '{}' is not a number", number, field[2], field[3]));
      found[field[2]] = *v;
    } else {
      // std::regex recurses per character: a long line (data, not a property assignment) is
      // skipped rather than risk the stack.
      std::smatch m;
      if (line.size() > 1000 || !std::regex_match(line, m, assign)) continue;  // other MATLAB statements
      const auto v = strict_number(m[2].str());
      if (v) found[m[1].str()] = *v;
    }
  }
  for (const auto& spec : target_keys(f.target)) {
    const auto it = found.find(spec.key);
    if (it == found.end()) {
      f.missing.push_back(spec.key);
    } else {
      f.values.push_back({spec, it->second});
    }
  }
}

}  // namespace

ParamsFile read_params_text(const std::string& text, const std::string& name, std::optional<Target> target) {
  ParamsFile f;
  f.path = name;
  if (target) {
    f.target = *target;
  } else {
    const auto t = detect(text, name);
    if (!t) {
      bad(name, "cannot tell which filter this file is for; fix: give --target T; targets: " + target_list());
    }
    f.target = *t;
    f.target_detected = true;
  }
  switch (f.target) {
    case Target::gtsam: read_json(f, text); break;
    case Target::px4:
    case Target::matlab: read_lines(f, text); break;
    default: read_yaml(f, text); break;
  }
  for (const auto& v : f.values) {
    if (!(std::isfinite(v.value) && v.value > 0.0)) {
      bad(name, fmt::format("{} = {:g} is not a positive number (a noise value is a standard deviation or "
                            "variance); fix: correct it, or remove the key to leave it unchecked",
                            v.spec.key, v.value));
    }
  }
  if (f.values.empty()) {
    std::string keys;
    for (const auto& k : target_keys(f.target)) {
      if (!keys.empty()) keys += ", ";
      keys += k.key;
    }
    bad(name, fmt::format("none of the {} noise keys ({}) is in the file; fix: check the file or --target",
                          target_name(f.target), keys));
  }
  return f;
}

ParamsFile read_params_file(const std::string& path, std::optional<Target> target) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the parameter file; fix: check the path");
  std::stringstream s;
  s << in.rdbuf();
  return read_params_text(s.str(), path, target);
}

}  // namespace imunoise::exports
