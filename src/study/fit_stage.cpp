// The fit stage of the study and its text table (moved here from the fit command).
#include "imunoise/study/fit_stage.hpp"

#include <cmath>

#include <fmt/core.h>

#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/preprocess/pipeline.hpp"
#include "imunoise/preprocess/pooled_deviation.hpp"
#include "imunoise/preprocess/temperature.hpp"
#include "imunoise/theo.hpp"

namespace imunoise::study {
namespace {

std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.5g}", v) : "-"; }

}  // namespace

fit::RecordInfo record_info(const Record& record) {
  return {record.source, record.rate_hz, record.n_samples, record.rate_unit, unit_label(record),
          is_gyro(record)};
}

fit::FitResult fit_curve(const Record& record, std::span<const DevPoint> oadev_points, std::size_t n_phase,
                         const fit::FitOptions& options, const std::vector<std::string>& warnings) {
  const double tau0_s = 1.0 / record.rate_hz;
  // The robust gmwm estimates come from the samples: the record's phase when the curve is of
  // the whole record (not of pooled segments, bins or MPI slices).
  const bool whole = n_phase == record.phase_si.size() && record.segments.size() <= 1;
  if (options.method == fit::Method::gmwm && options.gmwm.robust && !whole) {
    throw InputError(record.source + ": --robust needs the curve of one contiguous record in memory (this one "
                     "is split into segments, pooled or distributed); fix: fit without --robust, or without "
                     "--gaps split / --outliers reject / --mpi");
  }
  fit::FitResult result = fit::fit_allan(oadev_points, n_phase, tau0_s, options,
                                         whole ? std::span<const double>(record.phase_si) : std::span<const double>());
  result.summary.warnings.insert(result.summary.warnings.begin(), warnings.begin(), warnings.end());
  if (result.summary.termination == fit::Termination::degenerate_input ||
      result.summary.termination == fit::Termination::too_few_points) {
    throw InputError(record.source + ": cannot fit a noise model: " + result.summary.message);
  }
  result.coefficients.quantity = record.rate_unit.quantity == Quantity::acceleration
                                     ? Quantity::acceleration
                                     : Quantity::angular_rate;
  return result;
}

fit::FitResult fit_channel(const Record& record, const fit::FitOptions& options,
                           const TauGrid& grid) {
  const double tau0_s = 1.0 / record.rate_hz;
  auto warnings = fit::record_warnings(record.phase_si, tau0_s);
  if (fit::is_constant_record(record.phase_si, tau0_s)) {
    throw InputError(record.source + ": the rate is constant (all-zero or a fixed value): there is "
                     "no noise to identify; check --column and the file");
  }
  const auto factors = estimator_averaging_factors(Estimator::oadev, grid, record.rate_hz,
                                                   record.phase_si.size());
  std::vector<DevPoint> points;
  std::size_t n_phase = record.phase_si.size();
  if (record.segments.size() > 1) {
    // A split record: the pooled oadev (no term spans a break; preprocess/pooled_deviation.hpp)
    // with the covariance of one record of the segments' summed length (sum of their angle
    // samples), which counts 2 m (K - 1) terms more than the K segments hold at factor m.
    preprocess::PoolOptions pool;
    pool.level = options.level;
    auto pooled = preprocess::pooled_deviation(Estimator::oadev, record.rate_si, record.segments, tau0_s, factors, pool);
    points = std::move(pooled.points);
    n_phase = 0;
    for (const auto& s : record.segments) n_phase += s.size() + 1;
    warnings.push_back("split record: fitted to the oadev pooled over " + std::to_string(record.segments.size()) +
                       " segments, with the estimate covariance of one record of their summed length");
  } else {
    points = oadev(record.phase_si, tau0_s, factors);
  }
  return fit_curve(record, points, n_phase, options, warnings);
}

void add_provenance(const Record& record, const fit::FitOptions& bin_fit, nlohmann::json& document) {
  if (!record.format.empty()) {
    document["recording"] = {{"format", record.format}, {"stream", record.stream}, {"channel", record.channel}};
  }
  if (!record.preprocessing.empty()) document["preprocessing"] = record.preprocessing;
  if (record.davar) document["davar"] = preprocess::davar_json(*record.davar);
  if (!record.temperature_bins.empty()) {
    document["temperature_bins"] = preprocess::temperature_bins_json(record.temperature_bins, record_info(record), bin_fit);
  }
}

std::string fit_table(const Record& record, const fit::FitOptions& options,
                     const fit::FitResult& r) {
  const double f = record.rate_unit.to_si;
  const auto names = fit::coefficient_units(unit_label(record));
  std::string out = fmt::format("# {}: {} samples at {:.9g} Hz; method {}, {:g}% intervals\n",
                                record.source, record.n_samples, record.rate_hz,
                                fit::method_name(options.method), 100 * options.level);
  out += fmt::format("{:<4} {:>13} {:>13} {:>13} {:<18} {:>5}  {}\n", "term", "value", "ci_low",
                     "ci_high", "unit", "ident", "customary");
  for (int j = 0; j < fit::kTermCount; ++j) {
    const auto& c = fit::coefficient(r.coefficients, j);
    std::string cust;
    if (is_gyro(record)) {
      const auto& cu = fit::customary_unit(j);
      cust = fmt::format("{} [{}, {}] {}", cell(c.value / cu.to_si), cell(c.ci_low / cu.to_si),
                         cell(c.ci_high / cu.to_si), cu.name);
    }
    out += fmt::format("{:<4} {:>13} {:>13} {:>13} {:<18} {:>5}  {}\n", fit::term_name(j),
                       cell(c.value / f), cell(c.ci_low / f), cell(c.ci_high / f),
                       names[static_cast<std::size_t>(j)],
                       c.identified ? "yes" : "no", cust);
  }
  auto extra_row = [&](const char* name, const Coefficient& c, double to_unit,
                       const std::string& unit) {
    std::string cust;
    if (is_gyro(record) && unit == unit_label(record)) {
      const auto& cu = customary_gyro_B;
      cust = fmt::format("{} [{}, {}] {}", cell(c.value / cu.to_si), cell(c.ci_low / cu.to_si),
                         cell(c.ci_high / cu.to_si), cu.name);
    }
    out += fmt::format("{:<4} {:>13} {:>13} {:>13} {:<18} {:>5}  {}\n", name,
                       cell(c.value / to_unit), cell(c.ci_low / to_unit),
                       cell(c.ci_high / to_unit), unit, c.identified ? "yes" : "no", cust);
  };
  // One pair of rows per Gauss-Markov term, by correlation time (GMs/GMt, then GM2s/GM2t, ...).
  for (std::size_t i = 0; i < r.coefficients.gauss_markov.size(); ++i) {
    const auto& gm = r.coefficients.gauss_markov[i];
    const std::string id = i == 0 ? "GM" : fmt::format("GM{}", i + 1);
    extra_row((id + "s").c_str(), gm.sigma, f, unit_label(record));
    extra_row((id + "t").c_str(), gm.correlation_time_s, 1.0, "s");
  }
  if (const auto& sin = r.coefficients.sinusoid) {
    extra_row("SINa", sin->amplitude, f, unit_label(record));
    extra_row("SINf", sin->frequency_hz, 1.0, "Hz");
  }
  for (int j = 0; j < fit::kTermCount; ++j) {
    const auto& c = fit::coefficient(r.coefficients, j);
    if (!c.note.empty()) out += fmt::format("# {}: {}\n", fit::term_name(j), c.note);
  }
  if (r.extras.gauss_markov.requested) {
    out += fmt::format("# GM (Gauss-Markov sigma GMs, correlation time GMt): {}\n",
                       r.extras.gauss_markov.verdict);
  }
  if (r.extras.sinusoid.requested) {
    out += fmt::format("# SIN (sinusoid amplitude SINa, frequency SINf): {}\n",
                       r.extras.sinusoid.verdict);
  }
  const std::string eq12 =
      r.tau_opt_s > 0.0
          ? fmt::format("tau_opt = {:.6g} s, adev_min = {:.6g} {}", r.tau_opt_s,
                        std::sqrt(r.avar_min_eq2) / f, unit_label(record))
          : std::string("not available (they need both N and K identified)");
  out += fmt::format("# paper eqs. 1-2: {}; measured minimum {:.6g} {} at tau = {:.6g} s\n", eq12,
                     std::sqrt(r.avar_min_measured) / f, unit_label(record), r.tau_min_measured_s);
  out += "# " + r.summary.BriefReport() + "\n";
  for (const auto& w : r.summary.warnings) out += "# warning: " + w + "\n";
  if (r.summary.mismatch_scatter > 0.0) {
    out += fmt::format("# model mismatch: {:.3g}% scatter of sigma^2 per tau; chi2/dof with it {:.3g}\n",
                       100 * r.summary.mismatch_scatter, r.summary.chi2_dof_with_mismatch);
  }
  out += fmt::format("{:>13} {:>13} {:>13} {:>9} {:>4}\n", "tau [s]", "adev", "model", "resid/sd",
                     "term");
  for (const auto& p : r.residuals) {
    out += fmt::format("{:>13.6g} {:>13.6g} {:>13.6g} {:>9} {:>4}\n", p.tau_s,
                       std::sqrt(p.avar) / f, std::sqrt(p.avar_model) / f,
                       p.used ? fmt::format("{:+.2f}", p.normalized) : std::string("excluded"),
                       p.dominant_term >= 0 ? fit::term_name(p.dominant_term) : "-");
  }
  return out;
}

std::string spec_table(const nlohmann::json& c) {
  if (c.is_null()) return "";
  const auto text = [](const nlohmann::json& v) {
    if (!v.is_object() || v["value"].is_null()) return std::string("-");
    return fmt::format("{:.4g} {}", v["value"].get<double>(), v["unit"].get<std::string>());
  };
  std::string out = fmt::format(
      "datasheet comparison: {} ({}), {:g} % CI; pass if measured <= "
      "spec x (1 + tolerance)\n",
      c["spec"].get<std::string>(), c["source"].get<std::string>(),
      100.0 * c["confidence_level"].get<double>());
  out = fmt::format("{}{:<22} {:>24} {:>24} {:>22} {:>10} {:>10} {}\n", out, "term", "measured",
                    "in spec unit", "spec", "deviation", "CI/limit", "verdict");
  for (const auto& t : c["terms"]) {
    std::string spec = "-";
    if (t.contains("spec")) {
      spec = text(t["spec"]);
      if (t["spec"]["tolerance"].get<double>() != 0.0) {
        spec += fmt::format(" +{:g}%", 100.0 * t["spec"]["tolerance"].get<double>());
      }
    }
    const std::string deviation =
        t["deviation_percent"].is_null()
            ? std::string("-")
            : fmt::format("{:+.1f} %", t["deviation_percent"].get<double>());
    std::string verdict = t["verdict"].get<std::string>();
    const bool judged = verdict == "pass" || verdict == "fail";
    if (judged) verdict += t["conclusive"].get<bool>() ? " (conclusive)" : " (inconclusive)";
    out += fmt::format(
        "{:<22} {:>24} {:>24} {:>22} {:>10} {:>10} {}\n",
        fmt::format("{} {}", t["symbol"].get<std::string>(), t["title"].get<std::string>()),
        text(t["measured_customary"]),
        t.contains("measured_in_spec_unit") ? text(t["measured_in_spec_unit"]) : "-", spec,
        deviation, judged ? t["ci_vs_limit"].get<std::string>() : "-", verdict);
  }
  return out;
}

}  // namespace imunoise::study
