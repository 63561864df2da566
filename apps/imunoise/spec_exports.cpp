#include "spec_exports.hpp"

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/export/export_target.hpp"
#include "imunoise/spec/exports.hpp"
#include "imunoise/spec/write_exports.hpp"
#include "imunoise/spec/report.hpp"

namespace imunoise::cli {

void add_filter_export_options(CLI::App& app, FilterExportOptions& options) {
  app.add_option("--export", options.exports,
                 "Write the noise parameters for a filter, TARGET[:FILE] (repeatable; TARGET one of " +
                     exports::target_list() + "; default FILE name in the output directory; docs/exports.md)")
      ->type_name("TARGET[:FILE]");
  app.add_option("--inflate,--inflation", options.inflation,
                 "Multiply every exported noise value by F (variances by F^2); stated in each file; default 1")
      ->check(CLI::PositiveNumber);
  app.add_option("--kalibr-topic", options.kalibr_topic, "rostopic written to the Kalibr and OpenVINS files")
      ->capture_default_str();
  app.add_option("--px4-ekf-rate", options.px4_ekf_rate_hz,
                 "PX4 EKF prediction rate (Hz) the px4 export is discretised at: 1e6 / EKF2_PREDICT_US")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
}

namespace {

std::vector<exports::ExportSpec> parse_specs(const FilterExportOptions& options) {
  std::vector<exports::ExportSpec> specs;
  for (const auto& text : options.exports) specs.push_back(exports::parse_export_spec(text));
  return specs;
}

}  // namespace

void check_filter_exports(const FilterExportOptions& options, const std::string& directory) {
  exports::check_targets(parse_specs(options), directory, options.force);
}

nlohmann::json run_filter_exports(const FilterExportOptions& options, std::span<const exports::AxisFit> fits,
                                  double rate_hz, const std::string& source, const std::string& directory) {
  nlohmann::json written = nlohmann::json::array();
  const auto specs = parse_specs(options);
  if (specs.empty()) return written;
  auto model = exports::make_export_model(fits, rate_hz, options.inflation, source);
  model.topic = options.kalibr_topic;
  model.px4_ekf_rate_hz = options.px4_ekf_rate_hz;
  exports::write_targets(specs, model, directory, options.force);
  for (const auto& spec : specs) {
    for (const auto& line : exports::not_carried(model, exports::target_name(spec.target))) {
      fmt::print(stderr, "imunoise: warning: --export {}: {}\n", exports::target_name(spec.target), line);
    }
    for (const auto& path : exports::target_paths(spec, directory)) {
      written.push_back({{"target", exports::target_name(spec.target)}, {"path", path}, {"inflation", options.inflation}});
    }
  }
  return written;
}

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
  add_filter_export_options(app, options.filter);
}

nlohmann::json run_spec_exports(const SpecExportOptions& options,
                                const NoiseCoefficients& coefficients, double rate_hz) {
  // The comparison first: a spec of another sensor kind fails before any file is written.
  nlohmann::json comparison = nullptr;
  if (!options.spec.empty()) comparison = comparison_json(compare(coefficients, resolve_spec(options.spec)));
  write_exports({options.kalibr_path, options.kf_json_path, options.filter.inflation,
                 options.filter.kalibr_topic, options.force},
                coefficients, rate_hz);
  if (!options.kalibr_path.empty()) {
    for (const auto& line : not_carried(coefficients, "Kalibr")) fmt::print(stderr, "imunoise: warning: --kalibr: {}\n", line);
  }
  return comparison;
}

}  // namespace imunoise::cli
