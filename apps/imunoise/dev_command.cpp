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
#include "imunoise/preprocess/preprocess.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "imunoise/total.hpp"
#include "distributed_record.hpp"
#include "input_options.hpp"
#include "output.hpp"
#include "work_budget.hpp"

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

struct Curve {
  Estimator estimator;
  std::string label;  // estimator name; "<name>-bc" for a bias-corrected copy
  std::vector<DevPoint> points;  // in the output unit
  std::string unit;
  std::vector<PointConfidence> confidence;  // empty with --no-ci
  std::vector<std::size_t> skipped;  // factors left out by --time-budget
  std::string note;                  // why, and how to get them; or how it was computed
  std::optional<TheoBiasFactor> theobr_factor;
};

std::size_t minimum_rate_samples(Estimator estimator) {
  std::size_t n_phase = 2;
  while (max_averaging_factor(estimator, n_phase) == 0) ++n_phase;
  return n_phase - 1;
}

nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string format_json(const PhaseRecord& record, const std::vector<Curve>& curves) {
  auto array = nlohmann::json::array();
  for (const auto& curve : curves) {
    nlohmann::json object{{"estimator", curve.label},
                          {"input", input_kind_name(record.kind)},
                          {"rate_hz", record.rate_hz},
                          {"n_samples", record.n_samples},
                          {"unit", curve.unit}};
    auto points = nlohmann::json::array();
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      const auto& p = curve.points[i];
      nlohmann::json point{{"m", p.m}, {"tau_s", p.tau_s}, {"dev", json_number(p.dev)}, {"n", p.n},
                           {"edf", json_number(p.edf)}, {"ci_low", json_number(p.ci_low)},
                           {"ci_high", json_number(p.ci_high)},
                           {"alpha", p.alpha == std::numeric_limits<int>::min()
                                         ? nlohmann::json(nullptr) : nlohmann::json(p.alpha)}};
      if (i < curve.confidence.size()) {
        const auto& c = curve.confidence[i];
        point["alpha_method"] = noise_id_method_name(c.noise.method);
        point["edf_method"] = edf_method_name(c.edf.method);
        if (!c.note.empty()) point["note"] = c.note;
      }
      points.push_back(std::move(point));
    }
    object["points"] = std::move(points);
    if (curve.label != estimator_name(curve.estimator)) object["bias_corrected"] = true;
    if (!curve.skipped.empty()) object["skipped_factors"] = curve.skipped;
    if (!curve.note.empty()) object["note"] = curve.note;
    if (curve.theobr_factor) {
      object["theobr_bias_factor"] = {{"avar_over_theo1", curve.theobr_factor->avar_over_theo1},
                                      {"ratios", curve.theobr_factor->ratios}};
    }
    if (!record.format.empty()) {
      object["recording"] = {{"format", record.format}, {"stream", record.stream},
                          {"channel", record.channel}};
    }
    if (!record.preprocessing.empty()) object["preprocessing"] = record.preprocessing;
    if (record.davar) {
      const auto& d = *record.davar;
      object["davar"] = {{"window_s", d.window_s}, {"step_s", d.step_s}, {"window_start_s", d.window_start_s},
                         {"tau_s", d.tau_s}, {"avar_si", d.avar}, {"reference_avar_si", d.reference_avar},
                         {"window_flagged", d.window_flagged}, {"stationary", d.stationary},
                         {"change_times_s", d.change_times_s}, {"suggested_skip_s", d.suggested_skip_s}};
    }
    if (!record.temperature_bins.empty()) {
      auto bins = nlohmann::json::array();
      for (const auto& b : record.temperature_bins) {
        bins.push_back({{"low", b.low}, {"high", b.high}, {"samples", b.samples}, {"runs", b.segments},
                        {"mean_temperature", b.mean_temperature}, {"bias_si", b.bias_si},
                        {"bias_stderr_si", b.bias_stderr_si}, {"N_si", json_number(b.random_walk_si)},
                        {"N_tau_s", b.random_walk_tau_s}, {"B_si", json_number(b.bias_instability_si)}});
      }
      object["temperature_bins"] = std::move(bins);
    }
    if (record.timing) {
      const auto& t = *record.timing;
      object["timing"] = {{"rate_hz", t.rate_hz}, {"median_dt_s", t.median_dt_s},
                          {"jitter_rel_std", t.jitter_rel_std}, {"jitter_rel_max", t.jitter_rel_max},
                          {"gaps", t.gaps.size()}, {"missing_samples", t.missing_samples}};
    }
    array.push_back(std::move(object));
  }
  return (array.size() == 1 ? array[0] : array).dump(1) + "\n";
}

std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.6e}", v) : "-"; }

// CSV: an absent number (no EDF or bounds for this estimator, or --no-ci) is an empty field.
std::string csv_number(double v, int digits) {
  return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : std::string();
}

std::string format_csv(const std::vector<Curve>& curves) {
  std::string out = "estimator,m,tau_s,dev,unit,n,edf,ci_low,ci_high,alpha\n";
  for (const auto& curve : curves) {
    for (const auto& p : curve.points) {
      out += fmt::format("{},{},{:.9g},{},{},{},{},{},{},{}\n",
                         curve.label, p.m, p.tau_s, csv_number(p.dev, 10), curve.unit, p.n,
                         csv_number(p.edf, 6), csv_number(p.ci_low, 10),
                         csv_number(p.ci_high, 10),
                         p.alpha == std::numeric_limits<int>::min() ? std::string()
                                                                     : std::to_string(p.alpha));
    }
  }
  return out;
}

std::string format_table(const PhaseRecord& record, const std::vector<Curve>& curves, double level) {
  std::string out = fmt::format("# {}: {} samples of {} at {:.9g} Hz ({:.6g} s)\n", record.source,
                                record.n_samples, input_kind_name(record.kind), record.rate_hz,
                                static_cast<double>(record.n_samples) / record.rate_hz);
  if (record.timing) {
    const auto& t = *record.timing;
    out += fmt::format("# time column: rate {:.9g} Hz from the median interval {:.6g} s; jitter "
                       "{:.3g}% rms, {:.3g}% max of the interval; {} gaps ({} missing samples)\n",
                       t.rate_hz, t.median_dt_s, 100 * t.jitter_rel_std, 100 * t.jitter_rel_max,
                       t.gaps.size(), t.missing_samples);
  }
  if (!record.channel.empty()) {
    out += fmt::format("# {}: {}{}{}\n", record.format, record.stream.empty() ? "" : record.stream + " ",
                       "channel ", record.channel);
  }
  for (const auto& line : record.preprocessing) out += "# preprocessing: " + line + "\n";
  for (const auto& curve : curves) {
    const std::string bounds = curve.confidence.empty() && !(curve.points.size() && std::isfinite(curve.points[0].ci_low))
                                   ? std::string("no confidence bounds (--no-ci)")
                                   : fmt::format("{:.1f}% confidence", 100 * level);
    out += fmt::format("\n{} [{}], {}{}\n", curve.label, curve.unit, bounds,
                       curve.label != estimator_name(curve.estimator)
                           ? " (bias-corrected for the noise type alpha)"
                           : "");
    out += fmt::format("{:>10} {:>13} {:>13} {:>11} {:>11} {:>13} {:>13} {:>5}\n", "m", "tau [s]",
                       "dev", "n", "edf", "ci_low", "ci_high", "alpha");
    for (const auto& p : curve.points) {
      out += fmt::format("{:>10} {:>13.6g} {:>13} {:>11} {:>11} {:>13} {:>13} {:>5}\n", p.m,
                         p.tau_s, cell(p.dev), p.n,
                         std::isfinite(p.edf) ? fmt::format("{:.4g}", p.edf) : std::string("-"),
                         cell(p.ci_low), cell(p.ci_high),
                         p.alpha == std::numeric_limits<int>::min() ? std::string("-")
                                                                     : std::to_string(p.alpha));
    }
    for (std::size_t i = 0; i < curve.confidence.size(); ++i) {
      if (!curve.confidence[i].note.empty()) {
        out += fmt::format("# note (m = {}): {}\n", curve.points[i].m, curve.confidence[i].note);
      }
    }
    if (!curve.note.empty()) out += fmt::format("# note: {}\n", curve.note);
  }
  return out;
}

std::string render(const DevOptionsCli& options, const PhaseRecord& record,
                   const std::vector<Curve>& curves) {
  if (options.format == "json") return format_json(record, curves);
  if (options.format == "csv") return format_csv(curves);
  return format_table(record, curves, options.ci_level);
}

// --mpi: the record is read in slices by the ranks and the mergeable sums are merged in a tree
// (distributed_record.hpp); rank 0 prints. No confidence intervals: the noise identification
// needs the whole record in one place.
void run_dev_mpi(const DevOptionsCli& options, const std::vector<Estimator>& estimators,
                 const TauGrid& grid) {
  if (options.bias_correct) throw InputError("--bias-correct does not apply to --mpi's estimators");
  const DistributedCurves dist = distributed_deviations(options.input, estimators, grid);
  if (!dist.root) return;
  std::vector<Curve> curves;
  for (std::size_t i = 0; i < estimators.size(); ++i) {
    const Estimator estimator = estimators[i];
    const bool integrated = reports_angle(estimator);
    const double to_si =
        integrated ? integral_unit(dist.record.rate_unit).to_si : dist.record.rate_unit.to_si;
    auto points = dist.curves[i];
    for (auto& p : points) p.dev /= to_si;
    curves.push_back({estimator, std::string(estimator_name(estimator)), std::move(points),
                      unit_label(dist.record, integrated), {}, {},
                      "--mpi: sums merged over the ranks; no confidence intervals (the noise "
                      "identification needs the whole record in one place)",
                      std::nullopt});
  }
  write_output(options.output, render(options, dist.record, curves));
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
  const TheoBrRatios theobr_ratios = parse_theobr_ratios(options.theobr_ratios);
  if (options.mpi) {
    run_dev_mpi(options, estimators, grid);
    return;
  }
  const PhaseRecord record = load_phase(options.input);
  const double tau0_s = 1.0 / record.rate_hz;

  std::vector<Curve> curves;
  for (const Estimator estimator : estimators) {
    const std::size_t max_m = max_averaging_factor(estimator, record.phase_si.size());
    if (max_m == 0) {
      throw InputError(record.source + ": " + std::to_string(record.n_samples) +
                       " samples are too few for " + std::string(estimator_name(estimator)) +
                       " (it needs at least " + std::to_string(minimum_rate_samples(estimator)) +
                       " rate samples); record longer");
    }
    const auto requested =
        estimator_averaging_factors(estimator, grid, record.rate_hz, record.phase_si.size());
    const BudgetSplit split =
        split_by_budget(estimator, record.phase_si.size(), requested, options.time_budget_s,
                        theobr_ratios);
    const auto& factors = split.kept;
    std::string skip_note;
    if (split.fixed_cost_too_high) {
      skip_note = fmt::format(
          "{} skipped: its bias factor alone (Theo1 at {} factors, cost growing as N^3) would take "
          "{}; raise --time-budget (0: no limit), or use theo1 with --bias-correct",
          estimator_name(estimator), theobr_ratio_count(record.phase_si.size(), theobr_ratios),
          duration_text(split.skipped_seconds));
      fmt::print(stderr, "imunoise: warning: {}\n", skip_note);
    } else if (!split.skipped.empty()) {
      skip_note = fmt::format(
          "{} at m >= {} (tau >= {:.6g} s) skipped: those {} taus would take {} (its cost grows "
          "as N m per tau); raise --time-budget (0: no limit) or choose taus with --taus/--af",
          estimator_name(estimator), split.skipped.front(),
          static_cast<double>(split.skipped.front()) * tau_per_factor(estimator) * tau0_s,
          split.skipped.size(), duration_text(split.skipped_seconds));
      fmt::print(stderr, "imunoise: warning: {}\n", skip_note);
    }
    std::vector<DevPoint> points;
    std::optional<TheoBiasFactor> theobr_factor;
    if (estimator == Estimator::theobr && !factors.empty()) {
      TheoBiasFactor kf;
      points = theobr(record.phase_si, tau0_s, factors, {options.threads}, theobr_ratios, &kf);
      theobr_factor = kf;
      skip_note = fmt::format(
          "ThêoBR variance = Theo1 variance x {:.6g} (Avar/Theo1 averaged over {} taus, {} rule){}{}",
          kf.avar_over_theo1, kf.ratios, options.theobr_ratios, skip_note.empty() ? "" : "; ",
          skip_note);
    } else if (!factors.empty() && record.segments.size() > 1) {
      // A split record (--gaps split, --outliers reject): the segments' Allan sums are pooled,
      // with chi-squared bounds from the summed edf (preprocess.hpp).
      if (estimator != Estimator::oadev) {
        throw InputError(record.source + ": the record is split into " + std::to_string(record.segments.size()) +
                         " segments, whose sums are pooled for oadev only; fix: --estimator oadev, or "
                         "drop --gaps split / --outliers reject");
      }
      points = preprocess::pooled_oadev(record.rate_si, record.segments, tau0_s, factors, options.ci_level);
      if (options.no_ci) {
        for (auto& p : points) p.ci_low = p.ci_high = p.edf = std::numeric_limits<double>::quiet_NaN();
      }
      skip_note = "pooled over " + std::to_string(record.segments.size()) +
                  " segments; bounds from the summed simple edf (n/m - 1 per segment)";
    } else if (!factors.empty()) {
      points = compute_deviation(estimator, record.phase_si, tau0_s, factors, {options.threads});
    }
    std::vector<PointConfidence> confidence;
    if (!options.no_ci && record.segments.size() <= 1) {
      ConfidenceOptions confidence_options;
      confidence_options.level = options.ci_level;
      confidence_options.forced_alpha = forced_alpha;
      confidence_options.threads = options.threads;
      confidence = fill_confidence(points, estimator, record.phase_si, confidence_options);
    }
    // SI inside, the input's unit at the edge: tdev, ttotdev, mtie, tierms are angles.
    const bool integrated = reports_angle(estimator);
    const double to_si = integrated ? integral_unit(record.rate_unit).to_si : record.rate_unit.to_si;
    for (auto& p : points) {
      p.dev /= to_si;
      p.ci_low /= to_si;
      p.ci_high /= to_si;
    }
    const std::string name(estimator_name(estimator));
    std::vector<DevPoint> corrected;
    const bool has_correction = estimator == Estimator::totdev || estimator == Estimator::mtotdev ||
                                estimator == Estimator::ttotdev ||
                                estimator == Estimator::htotdev || estimator == Estimator::theo1;
    if (options.bias_correct && has_correction) {
      corrected = points;
      apply_bias_correction(corrected, estimator, record.phase_si.size());
    }
    curves.push_back({estimator, name, std::move(points), unit_label(record, integrated), confidence,
                      split.skipped, skip_note, theobr_factor});
    if (options.bias_correct && has_correction) {
      curves.push_back({estimator, name + "-bc", std::move(corrected), unit_label(record, integrated),
                        std::move(confidence), split.skipped, skip_note, std::nullopt});
    }
  }
  std::string text;
  if (options.format == "json") {
    text = format_json(record, curves);
  } else if (options.format == "csv") {
    text = format_csv(curves);
  } else {
    text = format_table(record, curves, options.ci_level);
  }
  write_output(options.output, text);
  if (record.timing && !record.timing->gaps.empty()) {
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
                    "oadev mdev tdev hdev ohdev are merged in a tree (no confidence intervals; "
                    "docs/scale.md)");
  command->callback([options] { run_dev(*options); });
}

}  // namespace imunoise::cli
