// imunoise fleet: many sensors, one file each: every record studied (imunoise/study/sensor.hpp), then
// the fleet document, distributions, pass rate and outliers (imunoise/fleet/fleet.hpp) written
// to DIR/fleet.json and DIR/fleet.csv.
//
// Under `mpirun -np P` (P > 1) rank 0 hands out the files one at a time to ranks 1..P-1 as they
// become free (records of different lengths take different times) and puts each result in its
// file's place, so the outputs are byte for byte the serial run's. A file that fails is
// reported with its name and the run goes on (--keep-going, the default); --strict stops at the
// first failure. A rank that dies ends the whole run (mpirun aborts the job and names the rank).
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/fleet/fleet.hpp"
#include "imunoise/fleet/outcome_wire.hpp"
#include "imunoise/fleet/report.hpp"
#include "imunoise/study/write.hpp"
#include "imunoise/spec/spec.hpp"
#include "fit_options.hpp"
#include "input_options.hpp"
#include "mpi_session.hpp"
#include "output.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/parallel/task_farm.hpp"
#include "imunoise/study/sensor.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise::cli {
namespace {

struct FleetOptionsCli {
  MultiInputOptions inputs;  ///< the files; the load options are shared by every file
  FitOptionsCli fit;
  std::string dir;
  bool force = false;
  bool strict = false;
  bool keep_going = false;  ///< the default; accepted for scripts that say it
  std::string taus = "octave";
  std::string spec;
  double outlier_z = 3.5;
  std::string title = "imunoise fleet report";
  bool nav = false;
  double nav_hours = 1.0;
  bool quiet = false;
};

study::SensorOptions analysis_options(const FleetOptionsCli& options) {
  study::SensorOptions a;
  a.fit = to_fit_options(options.fit);
  a.grid = parse_tau_grid(options.taus);
  if (!options.spec.empty()) a.spec = resolve_spec(options.spec);  // a bad --spec fails once, not per file
  a.nav = options.nav;
  a.nav_hours = options.nav_hours;
  if (!(a.nav_hours > 0.0)) throw InputError("--nav-hours must be positive");
  return a;
}

// The per-file step (imunoise/fleet/fleet.hpp): load the record and study it.
fleet::SensorOutcome analyze_file(const FleetOptionsCli& options, const study::SensorOptions& analysis,
                                  std::size_t index) {
  load::LoadOptions input = options.inputs.load;
  input.file = options.inputs.files[index];
  input.column = options.inputs.columns;
  return fleet::study_file(input, analysis);
}

void report_failure(const fleet::SensorOutcome& outcome, bool strict) {
  if (!strict) {
    fmt::print(stderr, "imunoise: warning: {} (the fleet run goes on; --strict stops at the first "
                       "failed file)\n", outcome.error);
  }
}

[[noreturn]] void fail_strict(const fleet::SensorOutcome& outcome) {
  throw InputError(outcome.error + " (--strict: the fleet run stops at the first failed file; "
                   "without it the file is reported and the run goes on)");
}

// Test hook (tests/fleet): a worker rank given a file whose name ends with this text kills
// itself, standing in for a node that dies mid-run.
bool must_die(const std::string& file) {
  const char* suffix = std::getenv("IMUNOISE_TEST_RANK_DIES_ON");
  if (suffix == nullptr || *suffix == '\0') return false;
  const std::string s(suffix);
  return file.size() >= s.size() && file.compare(file.size() - s.size(), s.size(), s) == 0;
}

// Rank 0 of a parallel run: the files handed out as ranks become free, results in the files'
// order (imunoise/parallel/task_farm.hpp).
std::vector<fleet::SensorOutcome> dispatch(const FleetOptionsCli& options, const study::SensorOptions& analysis,
                                           parallel::Ranks& ranks) {
  std::vector<fleet::SensorOutcome> results(options.inputs.files.size());
  const fleet::SensorOutcome* first_failure = nullptr;
  const auto work = [&](std::size_t index) {
    if (must_die(options.inputs.files.at(index))) std::raise(SIGKILL);
    return fleet::encode_outcome(index, analyze_file(options, analysis, index));
  };
  const auto on_result = [&](std::size_t, const parallel::Bytes& bytes) {
    fleet::SensorOutcome outcome;
    const std::size_t index = fleet::decode_outcome(bytes, options.inputs.files, outcome);
    results[index] = std::move(outcome);
    if (!results[index].ok()) {
      report_failure(results[index], options.strict);
      if (options.strict && first_failure == nullptr) first_failure = &results[index];
    }
    return first_failure == nullptr;
  };
  parallel::run_task_farm(ranks, results.size(), work, on_result);
  if (first_failure != nullptr) fail_strict(*first_failure);
  return results;
}

void run_fleet(const FleetOptionsCli& options) {
  parallel::Ranks& ranks = mpi::start();
  const study::SensorOptions analysis = analysis_options(options);
  if (options.inputs.columns.find(',') != std::string::npos) {
    throw InputError("--column " + options.inputs.columns + ": the fleet studies one channel per file "
                     "(one sensor each); fix: name one column, or use analyze for several");
  }
  if (!(options.outlier_z > 0.0)) throw InputError("--outlier-z must be positive");
  const std::filesystem::path dir(options.dir);
  const auto json_path = (dir / "fleet.json").string();
  const auto csv_path = (dir / "fleet.csv").string();
  // Rank 0 checks the outputs before any work; every rank learns the verdict together.
  std::string error;
  if (ranks.rank() == 0) {
    try {
      fleet::prepare_output_dir(options.dir, options.force);
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  if (!ranks.all_ok(error.empty())) {
    if (ranks.rank() == 0) throw InputError(error);
    return;
  }
  std::vector<fleet::SensorOutcome> results;
  if (ranks.size() == 1) {
    for (std::size_t i = 0; i < options.inputs.files.size(); ++i) {
      results.push_back(analyze_file(options, analysis, i));
      if (!results.back().ok()) {
        if (options.strict) fail_strict(results.back());
        report_failure(results.back(), false);
      }
    }
  } else {
    results = dispatch(options, analysis, ranks);
    if (ranks.rank() != 0) return;
  }
  fleet::FleetRules rules;
  rules.outlier_z = options.outlier_z;
  const fleet::FleetSummary summary = fleet::summarize_fleet(results, rules);
  const nlohmann::json doc = fleet::fleet_document(results, summary);
  write_output({json_path, options.force}, doc.dump(1) + "\n");
  write_output({csv_path, options.force}, fleet::fleet_csv(results, summary));
  study::WriteOptions report_options;
  report_options.force = options.force;
  const auto report = fleet::write_fleet_report(doc, options.dir, report_options, options.title);
  if (!options.quiet) {
    for (const auto& note : report.notes) fmt::print(stderr, "imunoise: note: {}\n", note);
  }
  fmt::print("fleet: {}; wrote {}, {} and the report {}\n", fleet::summary_line(doc), json_path, csv_path,
             (dir / "report.html").string());
}

}  // namespace

void setup_fleet(CLI::App& app) {
  auto options = std::make_shared<FleetOptionsCli>();
  auto* command = app.add_subcommand(
      "fleet", "many sensors (one record each): per-sensor fit and datasheet verdict, coefficient "
               "distributions, pass rate, outliers -> DIR/fleet.json, DIR/fleet.csv, DIR/report.html|md "
               "with figures; also under "
               "mpirun -np P");
  add_multi_input_options(*command, options->inputs, "records, one per sensor");
  command->add_option("-o,--output", options->dir, "output directory")->required();
  command->add_flag("--force", options->force, "replace existing fleet.json / fleet.csv / report");
  command->add_option("--title", options->title, "title of the report")->capture_default_str();
  command->add_flag("-q,--quiet", options->quiet, "no notes on stderr about the report");
  command->add_flag("--strict", options->strict, "stop at the first file that cannot be analysed");
  command->add_flag("--keep-going", options->keep_going,
                    "report a file that cannot be analysed and go on (the default)");
  add_fit_options(*command, options->fit);
  command->add_option("--taus", options->taus, "tau grid of the Allan curves")->capture_default_str();
  command->add_option("--spec", options->spec, "datasheet: built-in name (tg100) or YAML file");
  command->add_flag("--nav", options->nav,
                    "each gyro's navigation error at the horizon (the study's models and latitude) "
                    "in fleet.json/csv and its distribution in the report");
  command->add_option("--nav-hours", options->nav_hours, "navigation horizon (h)")->capture_default_str();
  command->add_option("--outlier-z", options->outlier_z,
                      "robust z-score on log10 of a coefficient above which a sensor is an outlier")
      ->capture_default_str();
  command->callback([options] { run_fleet(*options); });
}

}  // namespace imunoise::cli
