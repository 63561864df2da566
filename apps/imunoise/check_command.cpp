// imunoise check: a user's filter parameter file (any --export target) against what a
// recording measures. Parses options, fits the recording's channels and hands the file and the
// measured model to the library's audit (imunoise/export/audit.hpp); exit 1 when a value is
// wrong or too small.
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "fit_options.hpp"
#include "imunoise/error.hpp"
#include "imunoise/export/audit.hpp"
#include "imunoise/export/export_model.hpp"
#include "imunoise/export/read_params.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/tau_grid.hpp"
#include "input_options.hpp"

namespace imunoise::cli {
namespace {

struct CheckOptions {
  std::string params;
  MultiInputOptions inputs;
  FitOptionsCli fit;
  std::string target;
  std::string format = "table";
  double px4_ekf_rate_hz = 100.0;
};

void run_check(const CheckOptions& o) {
  if (o.format != "json" && o.format != "table") {
    throw InputError("unknown --format '" + o.format + "'; use json or table");
  }
  std::optional<exports::Target> target;
  if (!o.target.empty()) target = exports::parse_target(o.target);
  const auto file = exports::read_params_file(o.params, target);  // before the fit: fail fast
  const fit::FitOptions fo = to_fit_options(o.fit);
  const auto plan = load::plan_channels(o.inputs.files, o.inputs.columns, "", o.inputs.load, false,
                                        [](const std::string&, const std::string&) {});
  std::vector<exports::AxisFit> fits;
  std::string sources;
  double rate_hz = 0.0;
  for (const auto& channel : plan) {
    if (!channel.note.empty()) fmt::print(stderr, "imunoise: note: {}\n", channel.note);
    Record record = load::load(channel.options);
    print_load_notes(record);
    record.name = channel.name;
    const auto result = study::fit_channel(record, fo, parse_tau_grid("octave"));
    fits.push_back(exports::axis_fit(record, result.coefficients));
    fits.back().channel = channel.name;
    if (sources.find(record.source) == std::string::npos) sources += (sources.empty() ? "" : ", ") + record.source;
    if (rate_hz == 0.0) rate_hz = record.rate_hz;
  }
  auto model = exports::make_export_model(fits, rate_hz, 1.0, sources);
  model.px4_ekf_rate_hz = o.px4_ekf_rate_hz;
  const auto result = exports::audit(file, model);
  if (o.format == "json") {
    fmt::print("{}\n", exports::audit_json(result).dump(1));
  } else {
    fmt::print("{}", exports::audit_table(result));
  }
  if (!result.ok) throw CLI::RuntimeError(1);
}

}  // namespace

void setup_check(CLI::App& app) {
  auto o = std::make_shared<CheckOptions>();
  auto* command = app.add_subcommand(
      "check", "a filter's noise parameter file (kalibr, openvins, vins, orbslam3, gtsam, px4, matlab, ros) "
               "against a recording: consistent, inflated, or wrong by a known mistake");
  command->add_option("params", o->params, "the parameter file to check")->required();
  add_multi_input_options(*command, o->inputs,
                          "the recording(s) to measure (text, raw binary, ROS 1 bag, MCAP, HDF5 or EuRoC CSV)");
  add_fit_options(*command, o->fit);
  command->add_option("--target", o->target,
                      "the file's filter: " + exports::target_list() + " (default: recognised from the file)");
  command->add_option("--format", o->format, "table or json")->capture_default_str();
  command->add_option("--px4-ekf-rate", o->px4_ekf_rate_hz,
                      "PX4 EKF prediction rate (Hz) = 1e6 / EKF2_PREDICT_US")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->callback([o] { run_check(*o); });
}

}  // namespace imunoise::cli
