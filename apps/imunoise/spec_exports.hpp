#pragma once
// Datasheet comparison and noise-model exports for the commands that produce noise
// coefficients (fit, analyze): options --spec, --kalibr, --kf-json, --inflation, --kalibr-topic.
//
// Use from a command:
//   SpecExportOptions spec_options;                 // member of the command's options
//   add_spec_export_options(*sub, spec_options);    // in setup_<cmd>
//   spec_options.force = output.force;              // the command's own --force (not added here)
//   json["spec_comparison"] = run_spec_exports(spec_options, coefficients, rate_hz);
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "imunoise/export/export_model.hpp"
#include "imunoise/noise_coefficients.hpp"
#include "imunoise/spec/comparison.hpp"
#include "imunoise/spec/spec.hpp"

namespace imunoise::cli {

/// --export TARGET[:FILE] (repeatable), --inflate F (alias --inflation), --kalibr-topic: the
/// filter files of fit and analyze (imunoise/export).
struct FilterExportOptions {
  std::vector<std::string> exports;    ///< --export TARGET[:FILE]
  double inflation = 1.0;              ///< --inflate F: factor on every noise value (> 0)
  std::string kalibr_topic = "/imu0";  ///< --kalibr-topic TOPIC: rostopic (Kalibr, OpenVINS)
  double px4_ekf_rate_hz = 100.0;      ///< --px4-ekf-rate HZ: 1e6 / EKF2_PREDICT_US
  bool force = false;                  ///< the command's own --force, copied in
};

/// Registers --export, --inflate/--inflation, --kalibr-topic and --px4-ekf-rate on `app`.
void add_filter_export_options(CLI::App& app, FilterExportOptions& options);

/// Parses the --export requests and refuses (InputError) an unknown target, two requests of
/// one file, or an existing file without --force: call before the command's work.
void check_filter_exports(const FilterExportOptions& options, const std::string& directory);

/// Writes the --export files (default names in `directory`, "" = the current directory) from
/// the fitted axes and returns [{"target", "path", "inflation"}] for the command's report.
nlohmann::json run_filter_exports(const FilterExportOptions& options,
                                  std::span<const exports::AxisFit> fits, double rate_hz,
                                  const std::string& source, const std::string& directory);

struct SpecExportOptions {
  std::string spec;          ///< --spec NAME|FILE: built-in name (tg100) or YAML file; empty: none
  std::string kalibr_path;   ///< --kalibr FILE: write a Kalibr imu.yaml; empty: none
  std::string kf_json_path;  ///< --kf-json FILE: write Kalman-filter parameters; empty: none
  FilterExportOptions filter;  ///< --export, --inflate (--inflation), --kalibr-topic
  bool force = false;                  ///< replace existing files; NOT registered here: copy the
                                       ///< command's own --force into it before run_spec_exports
};

/// Registers --spec, --kalibr, --kf-json and the filter-export options on `app`.
void add_spec_export_options(CLI::App& app, SpecExportOptions& options);

/// Writes the requested export files (never replacing an existing file unless options.force;
/// all targets are checked before any is written) and returns the datasheet comparison as
/// JSON (null when no --spec was given). Throws InputError for a bad spec, a spec of another
/// sensor kind, an existing output, or a Kalibr export of an accelerometer fit.
/// @param rate_hz sample rate of the record (Hz), for update_rate and the discrete values
nlohmann::json run_spec_exports(const SpecExportOptions& options,
                                const NoiseCoefficients& coefficients, double rate_hz);

}  // namespace imunoise::cli
