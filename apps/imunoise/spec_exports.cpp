#include "spec_exports.hpp"

#include <fmt/core.h>

#include <cmath>
#include <filesystem>

#include "imunoise/error.hpp"
#include "imunoise/spec/exports.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "output.hpp"

namespace imunoise::cli {

void add_spec_export_options(CLI::App& app, SpecExportOptions& options) {
  std::string names;
  for (const auto& name : builtin_spec_names()) names += (names.empty() ? "" : ", ") + name;
  app.add_option(
      "--spec", options.spec,
      "Compare with a datasheet: built-in name (" + names + ") or YAML spec file (docs/spec.md)");
  app.add_option("--kalibr", options.kalibr_path,
                 "Write a Kalibr imu.yaml (noise density N in rad/s/sqrt(Hz), random walk K in "
                 "rad/s^2/sqrt(Hz)) to FILE");
  app.add_option("--kf-json", options.kf_json_path,
                 "Write Kalman-filter noise parameters (white-noise PSD, Gauss-Markov sigma and "
                 "T_c, random-walk PSD; SI, units in the file) to FILE as JSON");
  app.add_option("--inflation", options.inflation,
                 "Multiply the Kalibr noise values by X (recorded in the file; default 1)")
      ->check(CLI::PositiveNumber);
  app.add_option("--kalibr-topic", options.kalibr_topic, "rostopic written to the Kalibr file")
      ->capture_default_str();
}

namespace {

void check_target(const std::string& option, const std::string& path, bool force) {
  if (path == "-") {
    throw InputError(option +
                     " -: the export needs a file name (standard output carries the "
                     "command's report); fix: pass " +
                     option + " FILE");
  }
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !force) {
    throw InputError(path + ": file exists; imunoise does not overwrite it — choose another " +
                     option + " name or pass --force");
  }
}

}  // namespace


std::string format_spec_table(const nlohmann::json& c) { return study::spec_table(c); }

std::string format_spec_table(const SpecComparison& comparison) {
  return format_spec_table(comparison_json(comparison));
}

nlohmann::json run_spec_exports(const SpecExportOptions& options,
                                const NoiseCoefficients& coefficients, double rate_hz) {
  // Everything that can fail is checked before anything is written.
  std::optional<Spec> spec;
  if (!options.spec.empty()) spec = resolve_spec(options.spec);
  if (!options.kalibr_path.empty()) {
    check_target("--kalibr", options.kalibr_path, options.force);
    if (coefficients.quantity != Quantity::angular_rate) {
      throw InputError("--kalibr: the fit is of " +
                       std::string(quantity_name(coefficients.quantity)) +
                       "; the Kalibr file is written from a gyro fit (its accelerometer keys are "
                       "left as placeholders); fix: run the fit on a gyro channel");
    }
  }
  if (!options.kf_json_path.empty()) check_target("--kf-json", options.kf_json_path, options.force);
  if (!options.kalibr_path.empty() && options.kalibr_path == options.kf_json_path) {
    throw InputError("--kalibr and --kf-json name the same file '" + options.kalibr_path +
                     "'; fix: give two different file names");
  }
  nlohmann::json comparison = nullptr;
  if (spec) comparison = comparison_json(compare(coefficients, *spec));
  std::string kalibr_text;
  std::string kf_text;
  if (!options.kalibr_path.empty()) {
    kalibr_text =
        kalibr_imu_yaml(coefficients, nullptr, rate_hz, options.inflation, options.kalibr_topic);
  }
  if (!options.kf_json_path.empty()) {
    kf_text = kalman_parameters(coefficients, rate_hz).dump(1) + "\n";
  }
  if (!kalibr_text.empty()) write_output({options.kalibr_path, options.force}, kalibr_text);
  if (!kf_text.empty()) write_output({options.kf_json_path, options.force}, kf_text);
  return comparison;
}

}  // namespace imunoise::cli
