// imunoise fit: noise-model coefficients (paper eq. 5) with confidence intervals, the verdict
// on each term, fit diagnostics, and (through spec_exports) the datasheet comparison and the
// Kalibr / Kalman-filter exports.
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "distributed_record.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "input_options.hpp"
#include "sensor_analysis.hpp"
#include "output.hpp"
#include "spec_exports.hpp"
#include "study_record.hpp"

namespace imunoise::cli {
namespace {

struct FitOptionsCli {
  InputOptions input;
  OutputOptions output;
  SpecExportOptions spec;
  std::string method = "wls";
  std::string terms = "Q,N,B,K";
  std::string taus = "octave";
  std::string selection = "none";
  double level = 0.95;
  int min_dominant_taus = 2;
  bool gls = false;
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  bool keep_short_taus = false;
  bool exact_model = false;
  bool no_auto_terms = false;
  std::string format = "json";
  bool mpi = false;
};

void run_fit(FitOptionsCli& options) {
  if (options.format != "json" && options.format != "table") {
    throw InputError("unknown --format '" + options.format + "'; use json or table");
  }
  fit::FitOptions fo;
  fo.method = fit::parse_method(options.method);
  fo.level = options.level;
  fo.use_correlation = options.gls;
  fo.min_dominant_taus = options.min_dominant_taus;
  fo.selection = fit::parse_selection(options.selection);
  fo.tau_min_s = options.tau_min_s;
  fo.tau_max_s = options.tau_max_s;
  fo.exclude_distorted = !options.keep_short_taus;
  fo.model_mismatch = !options.exact_model;
  fo.auto_extra_terms = !options.no_auto_terms;
  fit::parse_terms(options.terms, fo);
  std::string why;
  if (!fo.IsValid(&why)) throw InputError("fit options: " + why);

  PhaseRecord loaded;
  std::optional<fit::FitResult> mpi_result;
  if (options.mpi) {
    // Each rank reads its slice; the oadev sums are merged in a tree (distributed_record.hpp).
    auto dist = distributed_deviations(options.input, {Estimator::oadev}, parse_tau_grid(options.taus));
    if (!dist.root) return;
    bool constant = true;
    for (const auto& p : dist.curves[0]) constant = constant && !(p.n > 0 && p.dev > 0.0);
    if (constant) {
      throw InputError(dist.record.source + ": the rate is constant (all-zero or a fixed value): there "
                       "is no noise to identify; check --column and the file");
    }
    const std::vector<std::string> warnings{
        "--mpi: the record checks (quantization, saturation, constant stretches) need the whole "
        "record in one place and were not run"};
    mpi_result = fit_curve(dist.record, dist.n_phase, dist.curves[0], warnings, fo).result;
    loaded = std::move(dist.record);
  } else {
    // A split record (--gaps split, --outliers reject) is fitted to its pooled oadev (fit_stage.hpp).
    // --temperature: each bin is fitted with this command's fit options.
    InputOptions input = options.input;
    input.temperature_fit = fo;
    loaded = load_phase(input);
  }
  // to_study_record moves the samples, the source and the timing; the provenance stays here.
  const study::Record record = to_study_record(std::move(loaded));
  const fit::FitResult result =
      mpi_result ? std::move(*mpi_result) : study::fit_channel(record, fo, parse_tau_grid(options.taus));

  nlohmann::json json = fit::report_json(study::record_info(record), fo, result);
  options.spec.force = options.output.force;
  json["spec_comparison"] = run_spec_exports(options.spec, result.coefficients, record.rate_hz);
  // Where the record came from and what preprocessing removed, so the fit names its input.
  if (!loaded.channel.empty()) {
    json["recording"] = {{"format", loaded.format}, {"stream", loaded.stream},
                      {"channel", loaded.channel}};
  }
  if (!loaded.preprocessing.empty()) json["preprocessing"] = loaded.preprocessing;
  if (!loaded.temperature_bins.empty()) {
    json["temperature_bins"] = preprocess::temperature_bins_json(loaded.temperature_bins, study::record_info(record), fo);
  }
  std::string preprocessing_lines;
  for (const auto& line : loaded.preprocessing) preprocessing_lines += "# preprocessing: " + line + "\n";
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
  auto options = std::make_shared<FitOptionsCli>();
  auto* command = app.add_subcommand(
      "fit", "noise-model coefficients (Q, N, B, K, R) with confidence intervals and diagnostics");
  add_input_options(*command, options->input);
  command->add_option("--method", options->method,
                      "wls (weighted NNLS, default), ols (the paper's least squares), slope "
                      "(IEEE 952 read-off)")
      ->capture_default_str();
  command->add_option("--terms", options->terms,
                      "terms to fit, comma list of Q,N,B,K,R (R only on request) and the optional "
                      "GM (first-order Gauss-Markov) and SIN (sinusoid), each kept only when the "
                      "data support it (wls)")
      ->capture_default_str();
  command->add_option("--taus", options->taus, "tau grid of the Allan curve: octave, decade, "
                                               "perdecade:K, ... (as dev)")
      ->capture_default_str();
  command->add_option("--level", options->level, "confidence level of the intervals")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 0.999));
  command->add_option("--selection", options->selection,
                      "wls model selection among the terms: none, aic, bic")
      ->capture_default_str();
  command->add_option("--min-dominant-taus", options->min_dominant_taus,
                      "wls: taus a term must dominate to stay in the fit")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  command->add_flag("--gls", options->gls,
                    "wls: whiten with the full correlation of the overlapping estimates "
                    "(generalised least squares) instead of the diagonal");
  command->add_option("--tau-min", options->tau_min_s,
                      "fit only taus >= this (s; 0: from the shortest)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--tau-max", options->tau_max_s, "fit only taus <= this (s; 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--keep-short-taus", options->keep_short_taus,
                    "do not leave out the shortest taus bent by the sensor's sampling chain "
                    "(filter, decimation)");
  command->add_flag("--exact-model", options->exact_model,
                    "weights and intervals assume the power-law model is exact (no "
                    "model-mismatch scatter, even when chi2 rejects the model)");
  command->add_flag("--no-auto-terms", options->no_auto_terms,
                    "wls: do not try the Gauss-Markov and sinusoid terms automatically when chi2 "
                    "rejects the power-law model and the curve has a bump");
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
