// imunoise analyze: the whole study of several recordings (files, or columns of one file) in
// one run, written as a report directory. Parses options, loads the channels and hands them
// to the library (imunoise/study); the report is rendered there.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "commands.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/export/export_model.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/load/load.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/summary.hpp"
#include "imunoise/study/study_fits.hpp"
#include "imunoise/study/write.hpp"
#include "fit_options.hpp"
#include "input_options.hpp"
#include "spec_exports.hpp"
#include "study_progress.hpp"

namespace imunoise::cli {
namespace {

struct AnalyzeOptionsCli {
  MultiInputOptions inputs;
  FitOptionsCli fit;
  std::string dir;
  bool force = false;
  std::string names;         // channel names replacing the derived ones
  std::string spec;
  std::string geometry;
  std::string estimators = "oadev";
  double ci_level = 0.683;
  double nav_hours = 1.0;
  std::string nav_models = study::StudyOptions{}.nav_models;
  bool keep_going = false;
  bool quiet = false;
  bool verbose = false;
  unsigned threads = 0;
  std::string title;
  FilterExportOptions filter;
};

void run_analyze(const AnalyzeOptionsCli& o) {
  if (o.dir.empty()) throw InputError("analyze needs -o DIR: the directory the report goes to");
  study::check_report_dir(o.dir, o.force);  // before the study's work, not after
  FilterExportOptions filter = o.filter;
  filter.force = o.force;
  check_filter_exports(filter, o.dir);
  study::StudyOptions so;
  so.curves.estimators = parse_estimator_list(o.estimators);
  validate_confidence_level(o.ci_level, "--ci");
  so.curves.ci_level = o.ci_level;
  so.curves.threads = o.threads;
  so.fit = to_fit_options(o.fit);
  if (!o.spec.empty()) so.spec = resolve_spec(o.spec);
  so.geometry = o.geometry;
  so.nav_hours = o.nav_hours;
  so.nav_models = o.nav_models;
  (void)nav::parse_models(so.nav_models);  // a bad list fails before the work
  so.keep_going = o.keep_going;
  if (!o.title.empty()) so.title = o.title;
  Progress progress(o.quiet);

  std::vector<study::FailedInput> failed;
  const auto plan = load::plan_channels(o.inputs.files, o.inputs.columns, o.names, o.inputs.load, o.keep_going,
                                       [&](const std::string& file, const std::string& error) {
                                         failed.push_back({file, error});
                                       });
  auto records = load::load_channels(
      plan, o.keep_going,
      [&](const std::string& file, const std::string& error) {
        failed.push_back({file, error});
        fmt::print(stderr, "imunoise: warning: skipped: {}\n", error);
      },
      [&](std::size_t i) { progress.update("reading " + plan[i].name, 0.0); });
  for (const auto& record : records) print_load_notes(record);
  study::Study result = study::run_study(std::move(records), so, failed,
                                         [&](std::string_view what, double fraction) {
                                           progress.update(std::string(what), fraction);
                                         });
  progress.update("writing the report", 1.0);
  const auto doc = study::study_json(result);
  const auto written = study::write_report(doc, o.dir, {o.force, "", "gnuplot"});
  progress.done();
  if (!filter.exports.empty()) {
    const study::StudyFits fits = study::study_fits(result);
    for (const auto& e : run_filter_exports(filter, fits.fits, fits.rate_hz, fits.sources, o.dir)) {
      fmt::print("export: {} ({})\n", e["path"].get<std::string>(), e["target"].get<std::string>());
    }
  }
  // One line a channel; the diagnostics are in the report (and here with --verbose).
  for (const auto& ch : result.channels) {
    fmt::print(stderr, "imunoise: {}\n", study::channel_summary(ch));
    if (!o.verbose) continue;
    for (const auto& w : ch.warnings) fmt::print(stderr, "imunoise: warning: {}: {}\n", ch.record.name, w);
  }
  for (const auto& n : written.notes) fmt::print(stderr, "imunoise: note: {}\n", n);
  fmt::print("report: {}\n", (std::filesystem::path(o.dir) / "report.html").string());
}

}  // namespace

void setup_analyze(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptionsCli>();
  auto* command = app.add_subcommand(
      "analyze", "the whole study of one or more recordings: curves with confidence, noise model, "
                 "datasheet verdict, report (HTML, JSON, Markdown, CSV, figures) in -o DIR");
  add_multi_input_options(*command, o->inputs,
                          "input files (text, raw binary, ROS 1 bag, MCAP, HDF5 or EuRoC CSV); - for "
                          "standard input");
  command->add_option("-o,--output", o->dir, "report directory (created when missing)")->required();
  command->add_flag("--force", o->force, "replace the report files of an existing DIR");
  command->add_option("--names", o->names, "channel names, comma list in file and column order");
  std::string names;
  for (const auto& name : builtin_spec_names()) names += (names.empty() ? "" : ", ") + name;
  command->add_option("--spec", o->spec,
                      "compare with a datasheet: built-in name (" + names + ") or YAML file");
  command->add_option("--geometry", o->geometry,
                      "redundant-unit geometry of the channels (e.g. tetra): fused axes and "
                      "fault detection");
  command->add_option("--estimator", o->estimators,
                      "curves to compute (comma list, as dev); oadev is always computed")
      ->capture_default_str();
  add_fit_options(*command, o->fit);
  command->add_option("--ci", o->ci_level, "confidence level of the curves' bars")
      ->capture_default_str();
  command->add_option("--nav-hours", o->nav_hours, "duration of the navigation-error curves (h)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--nav-models", o->nav_models,
                      "navigation models: schuler, covariance, montecarlo (1000 runs), paper (the paper's eq. 6), comma list")
      ->capture_default_str();
  command->add_flag("--keep-going", o->keep_going,
                    "an input or channel that fails is reported and the others are studied");
  command->add_flag("-q,--quiet", o->quiet, "no progress on standard error");
  command->add_flag("-v,--verbose", o->verbose,
                    "every diagnostic of every channel on standard error (by default one line a channel; "
                    "the report holds them all)");
  command->add_option("--threads", o->threads, "worker threads (0: all cores)");
  command->add_option("--title", o->title, "title of the report");
  add_filter_export_options(*command, o->filter);
  command->callback([o] { run_analyze(*o); });
}

}  // namespace imunoise::cli
