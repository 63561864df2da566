// imunoise fit: noise-model coefficients (paper eq. 5) with confidence intervals, the verdict
// on each term, fit diagnostics, and (through spec_exports) the datasheet comparison and the
// Kalibr / Kalman-filter exports.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "imunoise/export/export_model.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/preprocess/pipeline.hpp"
#include "imunoise/preprocess/temperature.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/parallel/distributed_fit.hpp"
#include "mpi_session.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "fit_options.hpp"
#include "input_options.hpp"
#include "output.hpp"
#include "spec_exports.hpp"

namespace imunoise::cli {
namespace {

struct FitCommandOptions {
  InputOptions input;
  FitOptionsCli fit;
  OutputOptions output;
  SpecExportOptions spec;
  std::string taus = "octave";
  std::string format = "json";
  bool mpi = false;
};

void run_fit(FitCommandOptions& options) {
  if (options.format != "json" && options.format != "table") {
    throw InputError("unknown --format '" + options.format + "'; use json or table");
  }
  const fit::FitOptions fo = to_fit_options(options.fit);
  options.spec.filter.force = options.output.force;
  check_filter_exports(options.spec.filter, "");  // refuse before the fit, not after
  Record record;
  fit::FitResult result;
  if (options.mpi) {
    auto fitted = parallel::fit_distributed(mpi::start(), options.input, parse_tau_grid(options.taus), fo);
    if (!fitted) return;
    record = std::move(fitted->first);
    result = std::move(fitted->second);
  } else {
    // A split record (--gaps split, --outliers reject) is fitted to its pooled oadev (fit_stage.hpp).
    // --temperature: each bin is fitted with this command's fit options.
    InputOptions input = options.input;
    input.temperature_fit = fo;
    record = load::load(input);
    print_load_notes(record);
    result = study::fit_channel(record, fo, parse_tau_grid(options.taus));
  }

  nlohmann::json json = fit::report_json(study::record_info(record), fo, result);
  options.spec.force = options.output.force;
  json["spec_comparison"] = run_spec_exports(options.spec, result.coefficients, record.rate_hz);
  const exports::AxisFit axis = exports::axis_fit(record, result.coefficients);
  json["exports"] = run_filter_exports(options.spec.filter, {&axis, 1}, record.rate_hz, record.source, "");
  study::add_provenance(record, fo, json);
  std::string preprocessing_lines;
  for (const auto& line : record.preprocessing) preprocessing_lines += "# preprocessing: " + line + "\n";
  std::string text;
  if (options.format == "json") {
    text = json.dump(1) + "\n";
  } else {
    text = preprocessing_lines + study::fit_table(record, fo, result) +
           study::spec_table(json["spec_comparison"]);
    if (!text.empty() && text.back() != '\n') text += '\n';
  }
  write_output(options.output, text);
  for (const auto& w : result.summary.warnings) fmt::print(stderr, "imunoise: warning: {}\n", w);
}

}  // namespace

void setup_fit(CLI::App& app) {
  auto options = std::make_shared<FitCommandOptions>();
  auto* command = app.add_subcommand(
      "fit", "noise-model coefficients (Q, N, B, K, R) with confidence intervals and diagnostics");
  add_input_options(*command, options->input);
  add_fit_options(*command, options->fit);
  command->add_option("--taus", options->taus, "tau grid of the Allan curve: octave, decade, "
                                               "perdecade:K, ... (as dev)")
      ->capture_default_str();
  command->add_option("--format", options->format, "json or table")->capture_default_str();
  command->add_option("-o,--output", options->output.path, "write to FILE instead of standard output");
  command->add_flag("--force", options->output.force, "replace existing output files");
  add_spec_export_options(*command, options->spec);
  command->add_flag("--mpi", options->mpi,
                    "under mpirun: each rank reads its own slice of the file and the oadev sums "
                    "are merged in a tree before the fit (docs/scale.md)");
  command->callback([options] { run_fit(*options); });
}

}  // namespace imunoise::cli
