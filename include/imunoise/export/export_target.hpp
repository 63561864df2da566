#pragma once
// The filters imunoise writes noise parameters for: their names on the command line, the
// default file names, and one call that renders a target's file(s).
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include "imunoise/export/export_model.hpp"

namespace imunoise::exports {

enum class Target { kalibr, openvins, vins, orbslam3, gtsam, px4, matlab, ros };

/// Every target, in the order of the help text.
const std::vector<Target>& all_targets();

/// "kalibr", "openvins", ...
std::string_view target_name(Target target);

/// "kalibr openvins vins orbslam3 gtsam px4 matlab ros", for help and error messages.
std::string target_list();

/// The target of a name; InputError "unknown target 'x'; targets: kalibr openvins ...".
Target parse_target(std::string_view name);

/// File written when the user names none: "kalibr_imu.yaml", "kalibr_imu_chain.yaml",
/// "vins_imu.yaml", "orbslam3_imu.yaml", "gtsam_imu.json" (+ "gtsam_imu.py"),
/// "px4_ekf2_imu.params", "imunoise_imu_params.m", "ros_imu_covariance.yaml".
std::string default_file_name(Target target);

/// One `--export TARGET[:FILE]` request.
struct ExportSpec {
  Target target;
  std::string path;  ///< empty: default_file_name in the output directory
};

/// Parses "TARGET" or "TARGET:FILE"; InputError for an unknown target or an empty FILE.
ExportSpec parse_export_spec(std::string_view text);

struct ExportFile {
  std::string path;
  std::string text;
};

/// The files of one request, at target_paths(spec, directory). Throws InputError when the
/// model lacks what the target needs.
std::vector<ExportFile> render_target(const ExportSpec& spec, const ExportModel& model,
                                      const std::string& directory);

/// The file(s) a request writes: its path, or default_file_name in `directory` ("" = the
/// current directory); gtsam adds the Python snippet beside the JSON (extension .py).
std::vector<std::string> target_paths(const ExportSpec& spec, const std::string& directory);

/// InputError when two requests name the same file, or (without `force`) a file exists: for
/// a command to call before its long work, so a refusal comes first.
void check_targets(std::span<const ExportSpec> specs, const std::string& directory, bool force);

/// Renders every request (paths resolved in `directory` when not given; a given relative
/// path is used as given), checks that no two name the same file and that none exists (unless
/// `force`), then writes them all; nothing is written when any check fails. Returns the files
/// written. Throws InputError.
std::vector<std::string> write_targets(std::span<const ExportSpec> specs, const ExportModel& model,
                                       const std::string& directory, bool force);

}  // namespace imunoise::exports
