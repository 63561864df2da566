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
#include "imunoise/fleet/study_files.hpp"
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

// Test hook (tests/fleet): a worker rank given a file whose name ends with this text kills
// itself, standing in for a node that dies mid-run.
bool must_die(const std::string& file) {
  const char* suffix = std::getenv("IMUNOISE_TEST_RANK_DIES_ON");
  if (suffix == nullptr || *suffix == '\0') return false;
  const std::string s(suffix);
  return file.size() >= s.size() && file.compare(file.size() - s.size(), s.size(), s) == 0;
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
  std::vector<load::LoadOptions> inputs;
  for (const auto& file : options.inputs.files) {
    inputs.push_back(options.inputs.load);
    inputs.back().file = file;
    inputs.back().column = options.inputs.columns;
  }
  fleet::StudyFilesOptions run;
  run.strict = options.strict;
  run.on_failure = [](const fleet::SensorOutcome& outcome) {
    fmt::print(stderr, "imunoise: warning: {} (the fleet run goes on; --strict stops at the first failed file)\n",
               outcome.error);
  };
  if (ranks.size() > 1) {
    run.before_file = [&](std::size_t i) {
      if (must_die(options.inputs.files[i])) std::raise(SIGKILL);
    };
  }
  const auto results = fleet::study_files(ranks, inputs, analysis, run);
  if (ranks.rank() != 0) return;
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
