// The deviation-curve stage of the study and the documents of `imunoise dev` (moved here from
// the command so that dev, analyze and Python render the same curves the same way).
#include "imunoise/study/curves.hpp"

#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/preprocess/pooled_deviation.hpp"
#include "imunoise/study/work_budget.hpp"
#include "imunoise/total.hpp"
#include "../core/prefaulted.hpp"

namespace imunoise::study {
namespace {

std::size_t minimum_rate_samples(Estimator estimator) {
  std::size_t n_phase = 2;
  while (max_averaging_factor(estimator, n_phase) == 0) ++n_phase;
  return n_phase - 1;
}

nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.6e}", v) : "-"; }

// CSV: an absent number (no EDF or bounds for this estimator, or --no-ci) is an empty field.
std::string csv_number(double v, int digits) {
  return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : std::string();
}

}  // namespace

std::vector<Curve> curves_from_points(const Record& record, const CurveOptions& options,
                                      const std::vector<std::vector<DevPoint>>& points_si,
                                      std::span<const double> identification_phase_si, std::size_t n_phase_total,
                                      const std::string& note) {
  ConfidenceOptions confidence;
  confidence.level = options.ci_level;
  confidence.forced_alpha = options.forced_alpha;
  confidence.threads = options.threads;
  confidence.n_phase_total = n_phase_total;
  std::vector<Curve> curves;
  for (std::size_t i = 0; i < options.estimators.size(); ++i) {
    const Estimator estimator = options.estimators[i];
    const bool integrated = reports_angle(estimator);
    const double to_si = integrated ? integral_unit(record.rate_unit).to_si : record.rate_unit.to_si;
    auto points = points_si[i];
    for (auto& p : points) p.dev /= to_si;
    std::vector<PointConfidence> info;
    if (!options.no_ci) info = fill_confidence(points, estimator, identification_phase_si, confidence);
    curves.push_back({estimator, std::string(estimator_name(estimator)), std::move(points),
                      unit_label(record, integrated), std::move(info), {}, note, std::nullopt});
  }
  return curves;
}

std::vector<Curve> compute_curves(const Record& record, const CurveOptions& options,
                                  const std::function<void(const std::string&)>& warn) {
  const double tau0_s = 1.0 / record.rate_hz;
  std::vector<Curve> curves;
  for (const Estimator estimator : options.estimators) {
    if (const auto why = record.segments.size() > 1 ? preprocess::pooling_refusal(estimator)
                                                    : std::string_view();
        !why.empty()) {
      throw InputError(record.source + ": the record is split into " + std::to_string(record.segments.size()) +
                       " segments and " + std::string(estimator_name(estimator)) + " cannot be pooled over them: " +
                       std::string(why) + "; fix: --estimator adev, oadev, mdev, tdev, hdev or ohdev, or drop "
                       "--gaps split / --outliers reject");
    }
    const std::size_t max_m = max_averaging_factor(estimator, record.phase_si.size());
    if (max_m == 0) {
      throw InputError(record.source + ": " + std::to_string(record.n_samples) +
                       " samples are too few for " + std::string(estimator_name(estimator)) +
                       " (it needs at least " + std::to_string(minimum_rate_samples(estimator)) +
                       " rate samples); record longer");
    }
    const auto requested = estimator_averaging_factors(estimator, options.grid, record.rate_hz,
                                                       record.phase_si.size());
    const BudgetSplit split = split_by_budget(estimator, record.phase_si.size(), requested,
                                              options.time_budget_s, options.theobr_ratios);
    const auto& factors = split.kept;
    std::string skip_note;
    if (split.fixed_cost_too_high) {
      skip_note = fmt::format(
          "{} skipped: its bias factor alone (Theo1 at {} factors, cost growing as N^3) would take "
          "{}; raise --time-budget (0: no limit), or use theo1 with --bias-correct",
          estimator_name(estimator),
          theobr_ratio_count(record.phase_si.size(), options.theobr_ratios),
          duration_text(split.skipped_seconds));
      if (warn) warn(skip_note);
    } else if (!split.skipped.empty()) {
      skip_note = fmt::format(
          "{} at m >= {} (tau >= {:.6g} s) skipped: those {} taus would take {} (its cost grows "
          "as N m per tau); raise --time-budget (0: no limit) or choose taus with --taus/--af",
          estimator_name(estimator), split.skipped.front(),
          static_cast<double>(split.skipped.front()) * tau_per_factor(estimator) * tau0_s,
          split.skipped.size(), duration_text(split.skipped_seconds));
      if (warn) warn(skip_note);
    }
    std::vector<DevPoint> points;
    std::vector<PointConfidence> pooled_confidence;
    std::optional<TheoBiasFactor> theobr_factor;
    if (estimator == Estimator::theobr && !factors.empty()) {
      TheoBiasFactor kf;
      points = theobr(record.phase_si, tau0_s, factors, {options.threads}, options.theobr_ratios,
                      &kf);
      theobr_factor = kf;
      skip_note = fmt::format(
          "ThêoBR variance = Theo1 variance x {:.6g} (Avar/Theo1 averaged over {} taus, {} rule){}{}",
          kf.avar_over_theo1, kf.ratios, options.theobr_ratios_name,
          skip_note.empty() ? "" : "; ", skip_note);
    } else if (!factors.empty() && record.segments.size() > 1) {
      // A split record (--gaps split, --outliers reject): the segments' sums are pooled, with
      // chi-squared bounds from the Satterthwaite-combined EDF (preprocess/pooled_deviation.hpp).
      preprocess::PoolOptions pool;
      pool.level = options.ci_level;
      pool.forced_alpha = options.forced_alpha;
      pool.no_ci = options.no_ci;
      pool.threads = options.threads;
      auto pooled = preprocess::pooled_deviation(estimator, record.rate_si, record.segments, tau0_s, factors, pool);
      points = std::move(pooled.points);
      pooled_confidence = std::move(pooled.confidence);
      skip_note = "pooled over " + std::to_string(record.segments.size()) +
                  " segments (no term spans a break); EDF per segment (Greenhall-Riley for the noise type "
                  "of the longest segment) combined by Satterthwaite";
    } else if (!factors.empty()) {
      points = compute_deviation(estimator, record.phase_si, tau0_s, factors, {options.threads});
    }
    std::vector<PointConfidence> confidence = std::move(pooled_confidence);
    if (!options.no_ci && record.segments.size() <= 1) {
      ConfidenceOptions confidence_options;
      confidence_options.level = options.ci_level;
      confidence_options.forced_alpha = options.forced_alpha;
      confidence_options.threads = options.threads;
      confidence = fill_confidence(points, estimator, record.phase_si, confidence_options);
    }
    // SI inside, the input's unit at the edge: tdev, ttotdev, mtie, tierms are angles.
    const bool integrated = reports_angle(estimator);
    const double to_si =
        integrated ? integral_unit(record.rate_unit).to_si : record.rate_unit.to_si;
    for (auto& p : points) {
      p.dev /= to_si;
      p.ci_low /= to_si;
      p.ci_high /= to_si;
    }
    const std::string name(estimator_name(estimator));
    std::vector<DevPoint> corrected;
    const bool has_correction = estimator == Estimator::totdev ||
                                estimator == Estimator::mtotdev ||
                                estimator == Estimator::ttotdev ||
                                estimator == Estimator::htotdev || estimator == Estimator::theo1;
    if (options.bias_correct && has_correction) {
      corrected = points;
      apply_bias_correction(corrected, estimator, record.phase_si.size());
    }
    const bool two_curves = options.bias_correct && has_correction;
    curves.push_back({estimator, name, std::move(points), unit_label(record, integrated),
                      two_curves ? confidence : std::move(confidence), split.skipped, skip_note,
                      theobr_factor});
    if (two_curves) {
      curves.push_back({estimator, name + "-bc", std::move(corrected),
                        unit_label(record, integrated), std::move(confidence), split.skipped,
                        skip_note, std::nullopt});
    }
  }
  return curves;
}

nlohmann::json curve_json(const Record& record, const Curve& curve) {
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
  if (record.timing) {
    const auto& t = *record.timing;
    object["timing"] = {{"rate_hz", t.rate_hz}, {"median_dt_s", t.median_dt_s},
                        {"jitter_rel_std", t.jitter_rel_std},
                        {"jitter_rel_max", t.jitter_rel_max},
                        {"gaps", t.gaps.size()}, {"missing_samples", t.missing_samples}};
  }
  return object;
}

nlohmann::json curves_json(const Record& record, const std::vector<Curve>& curves) {
  auto array = nlohmann::json::array();
  for (const auto& curve : curves) array.push_back(curve_json(record, curve));
  return array;
}

std::string curves_csv(const std::vector<Curve>& curves) {
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

std::string curves_table(const Record& record, const std::vector<Curve>& curves, double level) {
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
  for (const auto& line : table_notes(record)) out += "# " + line + "\n";
  // 98 characters a point: with every tau of a long record tens of MB, reserved and mapped once
  // instead of grown by doubling (each growth a copy into fresh pages).
  std::size_t n_points = 0;
  for (const auto& curve : curves) n_points += curve.points.size();
  detail::reserve_prefaulted(out, out.size() + 98 * n_points + 4096);
  for (const auto& curve : curves) {
    const std::string bounds = curve.confidence.empty() &&
                                       !(curve.points.size() && std::isfinite(curve.points[0].ci_low))
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

}  // namespace imunoise::study
