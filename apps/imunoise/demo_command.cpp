// imunoise demo: the paper's study on its bundled default (simulated TG-100 gyros with the
// coefficients of Table 2), written as a report, with a short summary on standard output.
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "imunoise/study/demo.hpp"
#include "imunoise/study/study.hpp"
#include "imunoise/study/write.hpp"
#include "study_progress.hpp"

namespace imunoise::cli {
namespace {

struct DemoOptionsCli {
  std::string dir = "imunoise-demo";
  bool force = false;
  bool quiet = false;
  double hours = 6.0;
  unsigned threads = 0;
};

void run_demo(const DemoOptionsCli& o) {
  const auto start = std::chrono::steady_clock::now();
  study::check_report_dir(o.dir, o.force);  // before minutes of work, not after
  Progress progress(o.quiet);
  study::DemoOptions demo;
  demo.duration_s = o.hours * 3600.0;
  demo.threads = o.threads;
  progress.update("simulating four TG-100 gyros (200 Hz)", 0.0);
  auto records = study::simulate_demo_records(demo);
  auto options = study::demo_study_options();
  options.curves.threads = o.threads;
  const study::Study result = study::run_study(
      std::move(records), options, {},
      [&](std::string_view what, double f) { progress.update(std::string(what), f); });
  progress.update("writing the report", 1.0);
  auto doc = study::study_json(result);
  doc["reference"] = study::demo_reference(result, demo);
  const auto written = study::write_report(doc, o.dir, {o.force, "", "gnuplot"});
  progress.done();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("imunoise demo: four simulated TG-100 gyros, the paper's Table 2, 200 Hz, {:g} h, "
             "seed {}\n\n",
             o.hours, demo.seed);
  fmt::print("{}", study::demo_summary(doc));
  for (const auto& n : written.notes) fmt::print(stderr, "imunoise: note: {}\n", n);
  fmt::print("\nreport: {}  ({:.1f} s)\n",
             (std::filesystem::path(o.dir) / "report.html").string(), seconds);
}

}  // namespace

void setup_demo(CLI::App& app) {
  auto o = std::make_shared<DemoOptionsCli>();
  auto* command = app.add_subcommand(
      "demo", "the paper's study on simulated data: four TG-100 gyros (Table 2), report in -o DIR");
  command->add_option("-o,--output", o->dir, "report directory")->capture_default_str();
  command->add_flag("--force", o->force, "replace the report files of an existing DIR");
  command->add_flag("-q,--quiet", o->quiet, "no progress on standard error");
  command->add_option("--hours", o->hours, "simulated record length (h); the paper's is 6")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 48.0));
  command->add_option("--threads", o->threads, "worker threads (0: all cores)");
  command->callback([o] { run_demo(*o); });
}

}  // namespace imunoise::cli
