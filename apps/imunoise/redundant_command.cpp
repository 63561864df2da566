// imunoise redundant: a redundant (non-orthogonal) gyro unit. Geometry analysis (gains, GDOP,
// parity, degraded geometries), the fused axes' noise from the sensors' fits (--from), fusion of
// synchronous recordings into body rates and parity residuals (--fuse ... -o FUSED.csv) and
// fault detection (--detect). The library does the work (include/imunoise/redundant/).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/fused_csv.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/redundant/geometry.hpp"
#include "imunoise/redundant/in_motion.hpp"
#include "imunoise/redundant/report.hpp"
#include "imunoise/study/in_motion.hpp"
#include "imunoise/study/in_motion_container.hpp"
#include "imunoise/study/in_motion_report.hpp"
#include "imunoise/study/write.hpp"
#include "imunoise/study/unit_fusion.hpp"
#include "imunoise/units.hpp"
#include "imunoise/load/load.hpp"
#include "input_options.hpp"
#include "output.hpp"

namespace imunoise::cli {
namespace {

struct RedundantOptionsCli {
  std::string geometry;
  std::vector<std::string> from;
  std::vector<std::string> fuse;
  std::vector<std::string> in_motion;   // --in-motion F1 ... Fn
  std::vector<std::string> statics;     // --static S1 ... Sn: the same sensors at rest
  bool per_sensor = false;              // --per-sensor: refuse a geometry without per-sensor curves
  bool keep_leakage = false;            // --keep-leakage: no regression on the fused motion
  bool timing = false;                  // --timing: also the leakage of sensors sampled at different instants
  std::vector<std::string> accel;       // --accel AX AY AZ ...: accelerometer triads (g-sensitivity)
  std::vector<std::string> accel_topics;  // --accel-topic T: a container's accelerometer topic(s)
  std::string accel_units = "m/s^2";
  std::string report;                   // --report DIR: the in-motion report (figures, tables)
  double ci_level = 0.683;
  load::LoadOptions load;    // how each --fuse recording is read (file set per recording)
  std::string output;        // -o FUSED.csv
  std::string json_output;   // --json FILE
  bool force = false;
  bool detect = false;
  redundant::DetectionOptions detection;
  std::string format = "json";
  unsigned threads = 0;
};

// One --fuse recording through the loader, its rate samples (SI) kept for the fusion. Without
// --units the recordings are in the unit of the --from fits, when those state one.
Record read_recording(const RedundantOptionsCli& o, const std::string& file, const Unit* fits_unit) {
  load::LoadOptions options = o.load;
  options.file = file;
  options.keep_rates = true;
  if (options.units.empty() && fits_unit != nullptr && fits_unit->name != "input unit") {
    options.units = fits_unit->name;
  }
  return load::load(options);
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    const auto comma = text.find(',', start);
    const auto piece = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!piece.empty()) out.push_back(piece);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// --in-motion: each sensor's noise while the unit moves (redundant/in_motion.hpp).
void run_in_motion(const RedundantOptionsCli& o, const redundant::Geometry& geometry, const Unit* fits_unit) {
  if (!o.fuse.empty() || o.detect || !o.output.empty()) {
    throw InputError("--in-motion cannot be combined with --fuse, --detect or -o: run them separately");
  }
  validate_confidence_level(o.ci_level, "--ci");
  if (!o.report.empty()) study::check_report_dir(o.report, o.force);  // before the work
  redundant::InMotionOptions options;
  options.require_per_sensor = o.per_sensor;
  options.ci_level = o.ci_level;
  options.remove_leakage = !o.keep_leakage;
  options.remove_timing_leakage = o.timing;
  std::vector<Record> recs;
  std::array<std::vector<double>, 3> force;
  std::vector<std::string> notes;
  if (o.in_motion.size() == 1 && study::is_container_file(o.in_motion.front())) {
    // The whole unit in one container (a PX4 log's instances, a bag's IMU topics): each instance on
    // its own clock, so the timing leakage is removed too.
    if (!o.accel.empty()) throw InputError("--accel is for separate files; a container's accelerometers: --accel-topic");
    load::LoadOptions lo = o.load;
    lo.file = o.in_motion.front();
    auto cu = study::read_container_unit(lo, split_list(o.load.topic), o.accel_topics);
    recs = std::move(cu.gyros);
    force = std::move(cu.specific_force_m_s2);
    notes = std::move(cu.notes);
    options.remove_timing_leakage = true;
  } else {
    if (!o.accel_topics.empty()) {
      throw InputError("--accel-topic applies to a container given as the one --in-motion file");
    }
    for (const auto& f : o.in_motion) recs.push_back(read_recording(o, f, fits_unit));
    if (o.load.units.empty() && fits_unit == nullptr) study::require_angular_rates(recs, "--in-motion");
    std::vector<Record> accels;
    for (const auto& f : o.accel) {
      load::LoadOptions lo = o.load;
      lo.file = f;
      lo.units = o.accel_units;
      lo.keep_rates = true;
      accels.push_back(load::load(lo));
    }
    force = study::mean_specific_force(accels, recs.empty() ? 0 : recs.front().rate_si.size());
  }
  const fit::FitOptions fit_options;
  auto unit = study::analyze_in_motion(geometry, std::move(recs), options, fit_options, force);
  unit.notes.insert(unit.notes.begin(), notes.begin(), notes.end());
  if (!o.statics.empty()) {
    std::vector<Record> statics;
    for (const auto& f : o.statics) statics.push_back(read_recording(o, f, fits_unit));
    study::compare_with_static(unit, std::move(statics), fit_options);
  }
  for (const auto& note : unit.notes) fmt::print(stderr, "imunoise: note: {}\n", note);
  nlohmann::json doc =
      redundant::report_json(redundant::analyze_unit(geometry), Unit{"rad/s", Quantity::angular_rate, 1.0}, nullptr);
  doc["in_motion"] = study::in_motion_json(unit, fit_options);
  if (!o.report.empty()) {
    study::WriteOptions wo;
    wo.force = o.force;
    const auto written = study::write_in_motion_report(doc, o.report, wo);
    for (const auto& note : written.notes) fmt::print(stderr, "imunoise: note: {}\n", note);
    fmt::print(stderr, "imunoise: wrote the in-motion report to {} ({} files)\n", written.dir, written.files.size());
  }
  const std::string text = o.format == "json" ? doc.dump(1) + "\n" : study::in_motion_table(unit);
  OutputOptions out;
  out.path = o.json_output;
  out.force = o.force;
  write_output(out, text);
}

void run_redundant(RedundantOptionsCli& o) {
  if (o.format != "json" && o.format != "table") throw InputError("unknown --format '" + o.format + "'; use json or table");
  const redundant::Geometry geometry = redundant::make_geometry(o.geometry);
  const std::size_t n = geometry.size();
  std::string why;
  if (!o.detection.IsValid(&why)) throw InputError("detection options: " + why);
  if (!std::isfinite(o.load.scale) || o.load.scale == 0.0) {
    throw InputError(fmt::format("--scale must be finite and non-zero, got {}", o.load.scale));
  }

  auto [models, unit] = redundant::models_in_unit(o.from, o.load.units, geometry);
  if (!o.in_motion.empty()) {
    run_in_motion(o, geometry, models.empty() ? nullptr : &unit);
    return;
  }
  if (o.per_sensor || o.keep_leakage || o.timing || !o.statics.empty() || !o.accel.empty() ||
      !o.accel_topics.empty() || !o.report.empty()) {
    throw InputError("--per-sensor, --keep-leakage, --timing, --static, --accel, --accel-topic and --report apply "
                     "to --in-motion F1 ... Fn");
  }
  if (o.detect && o.fuse.empty()) throw InputError("--detect runs on recordings: add --fuse F1 ... Fn");
  if (!o.output.empty() && o.fuse.empty()) throw InputError("-o writes the fused recording: add --fuse F1 ... Fn");

  redundant::AnalysisOptions ao;
  ao.detection = o.detection;
  std::optional<redundant::FusedRecord> fused;
  redundant::Analysis analysis;
  if (!o.fuse.empty()) {
    if (o.fuse.size() != n) {
      throw InputError(fmt::format("--fuse: {} recordings for the {} sensors of geometry {}; give "
                                   "one per sensing axis, in order", o.fuse.size(), n, geometry.name));
    }
    std::vector<Record> recs;
    for (const auto& f : o.fuse) recs.push_back(read_recording(o, f, models.empty() ? nullptr : &unit));
    if (o.load.units.empty() && models.empty()) {
      study::require_angular_rates(recs, "--fuse");  // containers state theirs (rad/s for Imu)
      unit = recs.front().rate_unit;
    }
    redundant::FusionOptions fo;
    fo.detect = o.detect;
    fo.detection = o.detection;
    fo.threads = o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
    auto unit_fusion = study::fuse_recordings(geometry, std::move(recs), std::move(models), ao, fo);
    for (const auto& note : unit_fusion.notes) fmt::print(stderr, "imunoise: note: {}\n", note);
    analysis = std::move(unit_fusion.analysis);
    fused = std::move(unit_fusion.fused);
    if (!o.output.empty()) redundant::write_fused_csv(o.output, o.force, *fused, unit, geometry.name, o.threads);
  } else {
    analysis = redundant::analyze_unit(geometry, models, ao);
  }
  const nlohmann::json doc = redundant::report_json(
      analysis, unit, fused && fused->detection ? &*fused->detection : nullptr);
  const std::string text = o.format == "json" ? doc.dump(1) + "\n" : redundant::report_table(doc);
  OutputOptions out;
  out.path = o.json_output;
  out.force = o.force;
  write_output(out, text);
}

}  // namespace

void setup_redundant(CLI::App& app) {
  auto o = std::make_shared<RedundantOptionsCli>();
  auto* c = app.add_subcommand("redundant",
                               "redundant gyro unit: geometry (gains, GDOP, parity), fused-axis noise, "
                               "fusion of recordings, fault detection and isolation");
  c->add_option("--geometry", o->geometry,
                "tetra, cone:N:DEG, 3+1, dodeca, or a YAML/CSV file of unit vectors or azimuth,elevation (deg)")
      ->required();
  c->add_option("--from", o->from, "the sensors' fits (imunoise fit --format json), one per axis, in order");
  c->add_option("--fuse", o->fuse, "synchronous recordings, one per axis, in order (any format dev reads)");
  c->add_option("--in-motion", o->in_motion,
                 "synchronous recordings taken while the unit moves, one per axis, in order: each "
                 "sensor's own noise from the parity space (the N-cornered hat) and its fit");
  c->add_option("--static", o->statics,
                 "with --in-motion: the same sensors' recordings at rest, in the same order: their fits and "
                 "the in-motion/static ratio of N, B, K");
  c->add_flag("--per-sensor", o->per_sensor,
              "with --in-motion: fail (exit 1) when the geometry cannot give every sensor its own curve");
  c->add_flag("--keep-leakage", o->keep_leakage,
              "with --in-motion: do not remove the motion leaking into the parity (scale-factor and "
              "misalignment errors, estimated by regression on the fused motion)");
  c->add_flag("--timing", o->timing,
              "with --in-motion: also remove the leakage of sensors sampled at different instants (regression "
              "on the motion's derivative); always on for a container's instances");
  c->add_option("--accel", o->accel,
                "with --in-motion: accelerometer recordings, x y z of each co-aligned triad in body axes: the "
                "gyros' g-sensitivity is estimated and removed (leakage.g_sensitivity)");
  c->add_option("--accel-units", o->accel_units, "unit of the --accel recordings")->capture_default_str();
  c->add_option("--accel-topic", o->accel_topics,
                "with --in-motion CONTAINER: accelerometer topic(s) (e.g. sensor_accel); a topic with both "
                "(vehicle_imu, sensor_msgs/Imu) gives them itself");
  c->add_option("--report", o->report,
                "with --in-motion: write a report directory (report.html/.md/.json, each sensor's in-motion and "
                "static curves on one figure)");
  c->add_option("--ci", o->ci_level, "with --in-motion: confidence level of the intervals (0-1)")->capture_default_str();
  add_load_options(*c, o->load);
  c->add_option("-o,--output", o->output, "write the fused recording (CSV t_s,x,y,z,p1..pk) to FILE");
  c->add_option("--json", o->json_output, "write the report to FILE instead of standard output");
  c->add_flag("--force", o->force, "replace existing output files");
  c->add_flag("--detect", o->detect, "fault detection and isolation on the recordings");
  c->add_option("--window", o->detection.window_s, "detection test window (s)")->capture_default_str();
  c->add_option("--reference", o->detection.reference_s, "detection reference window before it (s)")
      ->capture_default_str();
  c->add_option("--false-alarm-rate", o->detection.false_alarm_per_hour, "false alarms per hour of clean data")
      ->capture_default_str();
  c->add_option("--detection-probability", o->detection.detection_probability,
                "probability of detecting the minimum detectable fault in one test")
      ->capture_default_str();
  c->add_option("--format", o->format, "json or table")->capture_default_str();
  c->add_option("--threads", o->threads, "worker threads (0 = all cores)");
  c->callback([o] { run_redundant(*o); });
}

}  // namespace imunoise::cli
