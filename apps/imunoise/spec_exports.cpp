#include "spec_exports.hpp"

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/spec/write_exports.hpp"
#include "imunoise/spec/report.hpp"

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

nlohmann::json run_spec_exports(const SpecExportOptions& options,
                                const NoiseCoefficients& coefficients, double rate_hz) {
  // The comparison first: a spec of another sensor kind fails before any file is written.
  nlohmann::json comparison = nullptr;
  if (!options.spec.empty()) comparison = comparison_json(compare(coefficients, resolve_spec(options.spec)));
  write_exports({options.kalibr_path, options.kf_json_path, options.inflation, options.kalibr_topic, options.force},
                coefficients, rate_hz);
  return comparison;
}

}  // namespace imunoise::cli
