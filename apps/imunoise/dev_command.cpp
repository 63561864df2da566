// imunoise dev: deviation curves with n, EDF and confidence bounds.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <thread>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "imunoise/confidence/fill_confidence.hpp"
#include "imunoise/deviation.hpp"
#include "imunoise/error.hpp"
#include "imunoise/preprocess/pipeline.hpp"
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/total.hpp"
#include "imunoise/parallel/distributed_fit.hpp"
#include "mpi_session.hpp"
#include "imunoise/study/curves.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "input_options.hpp"
#include "output.hpp"

namespace imunoise::cli {
namespace {

struct DevOptionsCli {
  InputOptions input;
  OutputOptions output;
  std::string estimators = "oadev";
  std::string taus = "octave";
  std::string factors;
  double ci_level = 0.683;
  std::string noise_type;
  bool no_ci = false;
  bool bias_correct = false;
  std::string format = "table";
  unsigned threads = 0;
  double time_budget_s = 300.0;
  std::string theobr_ratios = "taylor-howe";
  bool mpi = false;
};

std::string render(const DevOptionsCli& options, const study::Record& record,
                   const std::vector<study::Curve>& curves) {
  if (options.format == "json") {
    auto array = study::curves_json(record, curves);
    for (auto& object : array) study::add_provenance(record, fit::FitOptions{}, object);
    return (array.size() == 1 ? array[0] : array).dump(1) + "\n";
  }
  if (options.format == "csv") return study::curves_csv(curves);
  return study::curves_table(record, curves, options.ci_level);
}

void run_dev(const DevOptionsCli& options) {
  if (options.format != "table" && options.format != "json" && options.format != "csv") {
    throw InputError("unknown --format '" + options.format + "'; use table, json or csv");
  }
  const auto estimators = parse_estimator_list(options.estimators);
  const TauGrid grid = options.factors.empty() ? parse_tau_grid(options.taus)
                                               : parse_factor_list(options.factors);
  if (!options.no_ci) validate_confidence_level(options.ci_level, "--ci");
  if (options.no_ci && options.bias_correct) {
    throw InputError("--bias-correct needs the noise type at each tau: drop --no-ci (the noise "
                     "type is identified, or forced with --noise-type)");
  }
  const std::optional<int> forced_alpha =
      options.noise_type.empty() ? std::nullopt : std::optional<int>(parse_noise_type(options.noise_type));
  study::CurveOptions co;
  co.estimators = estimators;
  co.grid = grid;
  co.ci_level = options.ci_level;
  co.no_ci = options.no_ci;
  co.forced_alpha = forced_alpha;
  co.bias_correct = options.bias_correct;
  co.threads = options.threads;
  co.time_budget_s = options.time_budget_s;
  co.theobr_ratios = parse_theobr_ratios(options.theobr_ratios);
  co.theobr_ratios_name = options.theobr_ratios;
  if (options.mpi) {  // each rank reads its slice; rank 0 prints (imunoise/parallel/distributed_fit.hpp)
    if (const auto dist = parallel::curves_distributed(mpi::start(), options.input, co)) {
      write_output(options.output, render(options, dist->first, dist->second));
    }
    return;
  }
  const Record record = load::load(options.input);
  print_load_notes(record);
  const auto curves = study::compute_curves(record, co, [](const std::string& note) {
    fmt::print(stderr, "imunoise: warning: {}\n", note);
  });
  write_output(options.output, render(options, record, curves));
  if (record.timing && !record.timing->gaps.empty() && options.input.gaps != "split") {
    fmt::print(stderr, "imunoise: warning: {} gaps ({} missing samples) were treated as equally "
                       "spaced (--allow-gaps)\n", record.timing->gaps.size(),
               record.timing->missing_samples);
  }
}

}  // namespace

void setup_dev(CLI::App& app) {
  auto options = std::make_shared<DevOptionsCli>();
  auto* command = app.add_subcommand("dev", "deviation curves (Allan family) with n, EDF and "
                                            "confidence bounds");
  add_input_options(*command, options->input);
  command->add_option("--estimator", options->estimators,
                      "estimator(s): adev oadev mdev tdev hdev ohdev totdev mtotdev ttotdev htotdev "
                      "theo1 theobr mtie tierms, comma-separated, or all")
      ->capture_default_str();
  command->add_option("--taus", options->taus,
                      "tau grid: octave, decade, all, perdecade:K, or taus in s (0.1,1,10)")
      ->capture_default_str();
  command->add_option("--af", options->factors, "explicit averaging factors (1,10,100)");
  command->add_option("--ci", options->ci_level, "confidence level of the bounds")
      ->capture_default_str();
  command->add_flag("--no-ci", options->no_ci, "skip noise identification and confidence bounds");
  command->add_flag("--bias-correct", options->bias_correct,
                    "also report totdev, mtotdev, ttotdev, htotdev, theo1 corrected for their "
                    "noise-type bias, as <name>-bc (docs/estimators.md)");
  command->add_option("--noise-type", options->noise_type,
                      "force the power-law noise type instead of identifying it: alpha -4..2 or "
                      "WHPM FLPM WHFM FLFM RWFM FWFM RRFM");
  command->add_option("--format", options->format, "table, json or csv")->capture_default_str();
  command->add_option("--threads", options->threads, "worker threads (0: all cores)");
  command->add_option("--time-budget", options->time_budget_s,
                      "seconds (estimated) that mtotdev, ttotdev, htotdev, theo1 and theobr may take "
                      "each; their longest taus beyond it are skipped with a note (0: no limit)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--theobr-ratios", options->theobr_ratios,
                      "how many Avar/Theo1 ratios ThêoBR's bias factor averages: taylor-howe "
                      "(N/30 - 3, Avar out to a tenth of the record) or stable32 (N/6 - 3, "
                      "Stable32's Run/Plot)")
      ->capture_default_str();
  command->add_option("-o,--output", options->output.path, "write to FILE instead of standard output");
  command->add_flag("--force", options->output.force, "replace an existing output file");
  command->add_flag("--mpi", options->mpi,
                    "under mpirun: each rank reads its own slice of the file, the sums of adev "
                    "oadev mdev tdev hdev ohdev are merged in a tree; confidence intervals count "
                    "the whole record, with the noise type identified on rank 0's slice "
                    "(docs/scale.md)");
  command->callback([options] { run_dev(*options); });
}

}  // namespace imunoise::cli
