#include "imunoise/export/export_target.hpp"

#include <filesystem>
#include <set>
#include <system_error>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/export/gtsam.hpp"
#include "imunoise/export/kalibr.hpp"
#include "imunoise/export/matlab.hpp"
#include "imunoise/export/openvins.hpp"
#include "imunoise/export/orbslam3.hpp"
#include "imunoise/export/px4.hpp"
#include "imunoise/export/ros.hpp"
#include "imunoise/export/vins.hpp"
#include "imunoise/io/atomic_output.hpp"

namespace imunoise::exports {

const std::vector<Target>& all_targets() {
  static const std::vector<Target> targets{Target::kalibr, Target::openvins, Target::vins,   Target::orbslam3,
                                           Target::gtsam,  Target::px4,      Target::matlab, Target::ros};
  return targets;
}

std::string_view target_name(Target target) {
  switch (target) {
    case Target::kalibr: return "kalibr";
    case Target::openvins: return "openvins";
    case Target::vins: return "vins";
    case Target::orbslam3: return "orbslam3";
    case Target::gtsam: return "gtsam";
    case Target::px4: return "px4";
    case Target::matlab: return "matlab";
    case Target::ros: return "ros";
  }
  return "?";
}

std::string target_list() {
  std::string out;
  for (auto t : all_targets()) {
    if (!out.empty()) out += ' ';
    out += target_name(t);
  }
  return out;
}

Target parse_target(std::string_view name) {
  for (auto t : all_targets()) {
    if (target_name(t) == name) return t;
  }
  throw InputError(fmt::format("unknown target '{}'; targets: {}", name, target_list()));
}

std::string default_file_name(Target target) {
  switch (target) {
    case Target::kalibr: return "kalibr_imu.yaml";
    case Target::openvins: return "kalibr_imu_chain.yaml";
    case Target::vins: return "vins_imu.yaml";
    case Target::orbslam3: return "orbslam3_imu.yaml";
    case Target::gtsam: return "gtsam_imu.json";
    case Target::px4: return "px4_ekf2_imu.params";
    case Target::matlab: return "imunoise_imu_params.m";
    case Target::ros: return "ros_imu_covariance.yaml";
  }
  return "";
}

ExportSpec parse_export_spec(std::string_view text) {
  const auto colon = text.find(':');
  ExportSpec spec{parse_target(text.substr(0, colon)), ""};
  if (colon != std::string_view::npos) {
    spec.path = std::string(text.substr(colon + 1));
    if (spec.path.empty() || spec.path == "-") {
      throw InputError(fmt::format("--export {}: needs a file name after ':' (standard output carries the "
                                   "command's report); fix: --export {} or --export {}:FILE",
                                   text, target_name(spec.target), target_name(spec.target)));
    }
  }
  return spec;
}

std::vector<std::string> target_paths(const ExportSpec& spec, const std::string& directory) {
  const std::string path =
      spec.path.empty()
          ? (std::filesystem::path(directory.empty() ? "." : directory) / default_file_name(spec.target))
                .lexically_normal()
                .string()
          : spec.path;
  if (spec.target != Target::gtsam) return {path};
  const std::string py = std::filesystem::path(path).replace_extension(".py").string();
  if (py == path) {
    throw InputError("--export gtsam:" + path +
                     ": the JSON and the Python snippet would be the same file; fix: name the JSON "
                     "file (e.g. gtsam_imu.json), the snippet goes beside it as .py");
  }
  return {path, py};
}

void check_targets(std::span<const ExportSpec> specs, const std::string& directory, bool force) {
  std::set<std::string> seen;
  for (const auto& spec : specs) {
    for (const auto& path : target_paths(spec, directory)) {
      if (!seen.insert(std::filesystem::path(path).lexically_normal().string()).second) {
        throw InputError("--export: two exports name the same file '" + path +
                         "'; fix: give each target its own FILE (--export TARGET:FILE)");
      }
      std::error_code ec;
      if (!force && std::filesystem::exists(path, ec)) {
        throw InputError(path + ": file exists; imunoise does not overwrite it -- choose another "
                                "--export TARGET:FILE or pass --force");
      }
    }
  }
}

std::vector<ExportFile> render_target(const ExportSpec& spec, const ExportModel& model,
                                      const std::string& directory) {
  const auto paths = target_paths(spec, directory);
  const std::string& path = paths.front();
  switch (spec.target) {
    case Target::kalibr: return {{path, kalibr_yaml(model)}};
    case Target::openvins: return {{path, openvins_yaml(model)}};
    case Target::vins: return {{path, vins_yaml(model)}};
    case Target::orbslam3: return {{path, orbslam3_yaml(model)}};
    case Target::gtsam: return {{path, gtsam_json(model).dump(1) + "\n"}, {paths[1], gtsam_python(model)}};
    case Target::px4: return {{path, px4_params(model)}};
    case Target::matlab: return {{path, matlab_script(model)}};
    case Target::ros: return {{path, ros_covariance_yaml(model)}};
  }
  return {};
}

std::vector<std::string> write_targets(std::span<const ExportSpec> specs, const ExportModel& model,
                                       const std::string& directory, bool force) {
  // Everything that can fail is checked before anything is written.
  check_targets(specs, directory, force);
  std::vector<ExportFile> files;
  for (const auto& s : specs) {
    for (auto& f : render_target(s, model, directory)) files.push_back(std::move(f));
  }
  std::vector<std::string> written;
  for (const auto& f : files) {
    io::AtomicOutput out(f.path, force);
    out.write(f.text.data(), f.text.size());
    out.commit();
    written.push_back(f.path);
  }
  return written;
}

}  // namespace imunoise::exports
