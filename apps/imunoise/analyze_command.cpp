// imunoise analyze: the whole study of several recordings (files, or columns of one file) in
// one run, written as a report directory. Parses options, loads the channels and hands them
// to the library (imunoise/study); the report is rendered there.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "commands.hpp"
#include "imunoise/comma_list.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/io/text_reader.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"
#include "input_options.hpp"
#include "study_progress.hpp"
#include "study_record.hpp"

namespace imunoise::cli {
namespace {

struct AnalyzeOptionsCli {
  std::vector<std::string> files;
  std::string dir;
  bool force = false;
  std::string columns;       // a,b,c: names or 0-based indexes; empty: every value column
  std::string names;         // channel names replacing the derived ones
  std::string time_column;
  double rate_hz = 0.0;
  std::string units;         // one unit, or one per channel
  std::string input = "rate";
  double scale = 1.0;
  double sensitivity = 0.0;
  std::string binary;
  std::size_t channels = 1;
  bool allow_gaps = false;
  bool davar = false;            // dynamic Allan variance heat map and stationarity verdict
  double davar_window_s = 0.0;
  std::string spec;
  std::string geometry;
  std::string estimators = "oadev";
  std::string method = "wls";
  double level = 0.95;
  double ci_level = 0.683;
  double nav_hours = 1.0;
  bool keep_going = false;
  bool quiet = false;
  unsigned threads = 0;
  std::string title;
};

std::string stem_of(const std::string& file) {
  if (file == "-") return "stdin";
  return std::filesystem::path(file).stem().string();
}

// The value columns of a text file: every header field (or index) but the time column. Only
// the first non-comment line is read here; the reader checks the rest.
std::vector<std::string> text_columns(const std::string& file, const std::string& time_column,
                                      bool& has_header) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open the file; check the path");
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    break;
  }
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  const auto hash = line.find('#');
  if (hash != std::string::npos) line.erase(hash);
  char sep = ' ';
  if (line.find('\t') != std::string::npos) sep = '\t';
  else if (line.find(';') != std::string::npos) sep = ';';
  else if (line.find(',') != std::string::npos) sep = ',';
  std::vector<std::string> fields;
  std::string field;
  auto flush = [&] {
    auto b = field.find_first_not_of(" \t\"");
    auto e = field.find_last_not_of(" \t\"");
    fields.push_back(b == std::string::npos ? std::string() : field.substr(b, e - b + 1));
    field.clear();
  };
  if (sep == ' ') {
    std::string token;
    for (char c : line) {
      if (c == ' ' || c == '\t') {
        if (!field.empty()) flush();
      } else {
        field += c;
      }
    }
    if (!field.empty()) flush();
  } else {
    for (char c : line) {
      if (c == sep) flush(); else field += c;
    }
    flush();
  }
  has_header = false;
  for (const auto& f : fields) has_header = has_header || !io::parse_number(f).has_value();
  std::vector<std::string> columns;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string name = has_header ? fields[i] : std::to_string(i);
    if (!time_column.empty() && (time_column == name || time_column == std::to_string(i))) continue;
    columns.push_back(has_header ? name : std::to_string(i));
  }
  return columns;
}

struct ChannelInput {
  InputOptions input;
  std::string name;
};

// Every (file, column) pair to load, with its name.
std::vector<ChannelInput> plan_channels(const AnalyzeOptionsCli& o,
                                        std::vector<study::FailedInput>& failed) {
  std::vector<ChannelInput> plan;
  const auto wanted = split_comma_list(o.columns);
  for (const auto& file : o.files) {
    InputOptions base;
    base.file = file;
    base.time_column = o.time_column;
    base.binary = o.binary;
    base.channels = o.channels;
    base.rate_hz = o.rate_hz;
    base.input = o.input;
    base.scale = o.scale;
    base.sensitivity = o.sensitivity;
    base.allow_gaps = o.allow_gaps;
    base.davar = o.davar;
    base.davar_window_s = o.davar_window_s;
    const bool binary = !o.binary.empty() ||
                        (file != "-" && io::binary_format_from_extension(file).has_value());
    std::vector<std::string> columns = wanted;
    bool named = false;
    if (columns.empty()) {
      if (binary) {
        for (std::size_t c = 0; c < o.channels; ++c) columns.push_back(std::to_string(c));
      } else if (file != "-") {
        try {
          columns = text_columns(file, o.time_column, named);
        } catch (const InputError& e) {
          if (!o.keep_going) throw;
          failed.push_back({file, e.what()});
          continue;
        }
      } else {
        columns.push_back("");
      }
    } else {
      named = true;
    }
    for (const auto& column : columns) {
      ChannelInput ch{base, ""};
      ch.input.column = column;
      const bool several = columns.size() > 1;
      const std::string label = named ? column : (binary ? "ch" + column : "col" + column);
      if (o.files.size() == 1) {
        ch.name = several || named ? label : stem_of(file);
      } else {
        ch.name = several ? stem_of(file) + ":" + label : stem_of(file);
      }
      if (columns.size() == 1 && column.empty()) ch.name = stem_of(file);
      plan.push_back(std::move(ch));
    }
  }
  const auto names = split_comma_list(o.names);
  if (!names.empty()) {
    if (names.size() != plan.size()) {
      throw InputError(fmt::format("--names gives {} names for {} channels; fix: one name per "
                                   "channel, in file and column order", names.size(), plan.size()));
    }
    for (std::size_t i = 0; i < plan.size(); ++i) plan[i].name = names[i];
  }
  const auto units = split_comma_list(o.units);
  if (units.size() > 1 && units.size() != plan.size()) {
    throw InputError(fmt::format("--units gives {} units for {} channels; fix: one unit for all, "
                                 "or one per channel in file and column order",
                                 units.size(), plan.size()));
  }
  for (std::size_t i = 0; i < plan.size(); ++i) {
    plan[i].input.units = units.empty() ? std::string() : units.size() == 1 ? units[0] : units[i];
  }
  return plan;
}

void run_analyze(const AnalyzeOptionsCli& o) {
  if (o.dir.empty()) throw InputError("analyze needs -o DIR: the directory the report goes to");
  study::check_report_dir(o.dir, o.force);  // before the study's work, not after
  study::StudyOptions so;
  so.curves.estimators = parse_estimator_list(o.estimators);
  validate_confidence_level(o.ci_level, "--ci");
  so.curves.ci_level = o.ci_level;
  so.curves.threads = o.threads;
  so.fit.method = fit::parse_method(o.method);
  so.fit.level = o.level;
  if (!o.spec.empty()) so.spec = resolve_spec(o.spec);
  so.geometry = o.geometry;
  so.nav_hours = o.nav_hours;
  so.keep_going = o.keep_going;
  if (!o.title.empty()) so.title = o.title;
  Progress progress(o.quiet);

  std::vector<study::FailedInput> failed;
  const auto plan = plan_channels(o, failed);
  std::vector<study::Record> records;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    progress.update("reading " + plan[i].name, 0.0);
    try {
      records.push_back(to_study_record(load_phase(plan[i].input), plan[i].name));
    } catch (const InputError& e) {
      if (!o.keep_going) {
        if (o.files.size() > 1 || plan.size() > 1) {
          throw InputError(std::string(e.what()) +
                           " (pass --keep-going to study the other inputs without it)");
        }
        throw;
      }
      failed.push_back({plan[i].input.file, e.what()});
      fmt::print(stderr, "imunoise: warning: skipped: {}\n", e.what());
    }
  }
  study::Study result = study::run_study(std::move(records), so, failed,
                                         [&](std::string_view what, double fraction) {
                                           progress.update(std::string(what), fraction);
                                         });
  progress.update("writing the report", 1.0);
  const auto doc = study::study_json(result);
  const auto written = study::write_report(doc, o.dir, {o.force, "", "gnuplot"});
  progress.done();
  for (const auto& ch : result.channels) {
    if (!ch.error.empty()) fmt::print(stderr, "imunoise: warning: {} failed: {}\n", ch.record.name, ch.error);
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
  command->add_option("files", o->files, "input files (text or raw binary); - for standard input")
      ->required();
  command->add_option("-o,--output", o->dir, "report directory (created when missing)")->required();
  command->add_flag("--force", o->force, "replace the report files of an existing DIR");
  command->add_option("--columns", o->columns,
                      "value columns (header names or 0-based indexes, comma list); default: "
                      "every column but the time column");
  command->add_option("--names", o->names, "channel names, comma list in file and column order");
  command->add_option("--time-column", o->time_column,
                      "column of timestamps (s, or integer ns); derives the rate and checks gaps");
  command->add_option("--rate", o->rate_hz, "sample rate (Hz)");
  command->add_option("--units", o->units,
                      "unit of the values (deg/s, rad/s, m/s^2, g, ...): one for every channel or "
                      "a comma list, one per channel");
  command->add_option("--input", o->input, "what the samples are: rate (freq) or angle (phase)")
      ->capture_default_str();
  command->add_option("--scale", o->scale, "multiply raw values by this factor");
  command->add_option("--sensitivity", o->sensitivity, "divide raw values by this sensitivity");
  command->add_option("--binary", o->binary, "raw binary samples: f32|f64|i16|i32[:le|be]");
  command->add_option("--channels", o->channels, "interleaved channels in binary input")
      ->capture_default_str();
  command->add_flag("--allow-gaps", o->allow_gaps, "treat gaps in the time column as equally spaced");
  command->add_flag("--davar", o->davar,
                    "dynamic Allan variance per channel: heat map and stationarity verdict in the report");
  command->add_option("--davar-window", o->davar_window_s, "DAVAR window (s); default record / 20");
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
  command->add_option("--method", o->method, "fit method: wls, ols, slope")->capture_default_str();
  command->add_option("--level", o->level, "confidence level of the fitted coefficients")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 0.999));
  command->add_option("--ci", o->ci_level, "confidence level of the curves' bars")
      ->capture_default_str();
  command->add_option("--nav-hours", o->nav_hours, "duration of the navigation-error curves (h)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_flag("--keep-going", o->keep_going,
                    "an input or channel that fails is reported and the others are studied");
  command->add_flag("-q,--quiet", o->quiet, "no progress on standard error");
  command->add_option("--threads", o->threads, "worker threads (0: all cores)");
  command->add_option("--title", o->title, "title of the report");
  command->callback([o] { run_analyze(*o); });
}

}  // namespace imunoise::cli
