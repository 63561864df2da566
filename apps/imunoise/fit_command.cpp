// imunoise fit: noise-model coefficients (paper eq. 5) with confidence intervals, the verdict
// on each term, fit diagnostics, and (through spec_exports) the datasheet comparison and the
// Kalibr / Kalman-filter exports.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "imunoise/allan.hpp"
#include "imunoise/error.hpp"
#include "imunoise/fit/fit.hpp"
#include "imunoise/fit/report.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/theo.hpp"
#include "distributed_record.hpp"
#include "input_options.hpp"
#include "sensor_analysis.hpp"
#include "output.hpp"
#include "spec_exports.hpp"

namespace imunoise::cli {
namespace {

struct FitOptionsCli {
  InputOptions input;
  OutputOptions output;
  SpecExportOptions spec;
  std::string method = "wls";
  std::string terms = "Q,N,B,K";
  std::string taus = "octave";
  std::string selection = "none";
  double level = 0.95;
  int min_dominant_taus = 2;
  bool gls = false;
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  bool keep_short_taus = false;
  bool exact_model = false;
  std::string format = "json";
  bool mpi = false;
};

std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.5g}", v) : "-"; }

bool gyro(const PhaseRecord& record) {
  return record.unit_given && record.rate_unit.quantity == Quantity::angular_rate;
}

std::string to_table(const PhaseRecord& record, const fit::FitOptions& options,
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
    if (gyro(record)) {
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
    if (gyro(record) && unit == unit_label(record)) {
      const auto& cu = customary_gyro_B;
      cust = fmt::format("{} [{}, {}] {}", cell(c.value / cu.to_si), cell(c.ci_low / cu.to_si),
                         cell(c.ci_high / cu.to_si), cu.name);
    }
    out += fmt::format("{:<4} {:>13} {:>13} {:>13} {:<18} {:>5}  {}\n", name,
                       cell(c.value / to_unit), cell(c.ci_low / to_unit),
                       cell(c.ci_high / to_unit), unit, c.identified ? "yes" : "no", cust);
  };
  if (const auto& gm = r.coefficients.gauss_markov) {
    extra_row("GMs", gm->sigma, f, unit_label(record));
    extra_row("GMt", gm->correlation_time_s, 1.0, "s");
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

void run_fit(FitOptionsCli& options) {
  if (options.format != "json" && options.format != "table") {
    throw InputError("unknown --format '" + options.format + "'; use json or table");
  }
  fit::FitOptions fo;
  fo.method = fit::parse_method(options.method);
  fo.level = options.level;
  fo.use_correlation = options.gls;
  fo.min_dominant_taus = options.min_dominant_taus;
  fo.selection = fit::parse_selection(options.selection);
  fo.tau_min_s = options.tau_min_s;
  fo.tau_max_s = options.tau_max_s;
  fo.exclude_distorted = !options.keep_short_taus;
  fo.model_mismatch = !options.exact_model;
  fit::parse_terms(options.terms, fo);
  std::string why;
  if (!fo.IsValid(&why)) throw InputError("fit options: " + why);

  PhaseRecord record;
  std::vector<DevPoint> points;
  std::size_t n_phase = 0;
  std::vector<std::string> warnings;
  if (options.mpi) {
    // Each rank reads its slice; the oadev sums are merged in a tree (distributed_record.hpp).
    auto dist = distributed_deviations(options.input, {Estimator::oadev}, parse_tau_grid(options.taus));
    if (!dist.root) return;
    record = std::move(dist.record);
    points = std::move(dist.curves[0]);
    n_phase = dist.n_phase;
    bool constant = true;
    for (const auto& p : points) constant = constant && !(p.n > 0 && p.dev > 0.0);
    if (constant) {
      throw InputError(record.source + ": the rate is constant (all-zero or a fixed value): there "
                       "is no noise to identify; check --column and the file");
    }
    warnings.push_back("--mpi: the record checks (quantization, saturation, constant stretches) "
                       "need the whole record in one place and were not run");
  } else {
    record = load_phase(options.input);
    if (record.segments.size() > 1) {
      throw InputError(record.source + ": fit needs one contiguous record, but --gaps split / --outliers reject "
                       "split it into " + std::to_string(record.segments.size()) + " segments; fix: fit the longest "
                       "gap-free stretch, or use --allow-gaps / --outliers report");
    }
    const double tau0_s = 1.0 / record.rate_hz;
    warnings = fit::record_warnings(record.phase_si, tau0_s);
    if (fit::is_constant_record(record.phase_si, tau0_s)) {
      throw InputError(record.source + ": the rate is constant (all-zero or a fixed value): there is "
                       "no noise to identify; check --column and the file");
    }
    const auto factors = estimator_averaging_factors(Estimator::oadev, parse_tau_grid(options.taus),
                                                     record.rate_hz, record.phase_si.size());
    points = oadev(record.phase_si, tau0_s, factors);
    n_phase = record.phase_si.size();
  }
  FitOutcome outcome = fit_curve(record, n_phase, points, warnings, fo);
  const fit::FitResult& result = outcome.result;

  nlohmann::json json = std::move(outcome.json);
  options.spec.force = options.output.force;
  json["spec_comparison"] = run_spec_exports(options.spec, result.coefficients, record.rate_hz);
  // Where the record came from and what preprocessing removed (issue 16).
  if (!record.channel.empty()) {
    json["recording"] = {{"format", record.format}, {"stream", record.stream},
                      {"channel", record.channel}};
  }
  if (!record.preprocessing.empty()) json["preprocessing"] = record.preprocessing;
  std::string preprocessing_lines;
  for (const auto& line : record.preprocessing) preprocessing_lines += "# preprocessing: " + line + "\n";
  std::string text;
  if (options.format == "json") {
    text = json.dump(1) + "\n";
  } else {
    text = preprocessing_lines + to_table(record, fo, result) + format_spec_table(json["spec_comparison"]);
    if (!text.empty() && text.back() != '\n') text += '\n';
  }
  write_output(options.output, text);
  for (const auto& w : result.summary.warnings) fmt::print(stderr, "imunoise: warning: {}\n", w);
}

}  // namespace

void setup_fit(CLI::App& app) {
  auto options = std::make_shared<FitOptionsCli>();
  auto* command = app.add_subcommand(
      "fit", "noise-model coefficients (Q, N, B, K, R) with confidence intervals and diagnostics");
  add_input_options(*command, options->input);
  command->add_option("--method", options->method,
                      "wls (weighted NNLS, default), ols (the paper's least squares), slope "
                      "(IEEE 952 read-off)")
      ->capture_default_str();
  command->add_option("--terms", options->terms,
                      "terms to fit, comma list of Q,N,B,K,R (R only on request) and the optional "
                      "GM (first-order Gauss-Markov) and SIN (sinusoid), each kept only when the "
                      "data support it (wls)")
      ->capture_default_str();
  command->add_option("--taus", options->taus, "tau grid of the Allan curve: octave, decade, "
                                               "perdecade:K, ... (as dev)")
      ->capture_default_str();
  command->add_option("--level", options->level, "confidence level of the intervals")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 0.999));
  command->add_option("--selection", options->selection,
                      "wls model selection among the terms: none, aic, bic")
      ->capture_default_str();
  command->add_option("--min-dominant-taus", options->min_dominant_taus,
                      "wls: taus a term must dominate to stay in the fit")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  command->add_flag("--gls", options->gls,
                    "wls: whiten with the full correlation of the overlapping estimates "
                    "(generalised least squares) instead of the diagonal");
  command->add_option("--tau-min", options->tau_min_s,
                      "fit only taus >= this (s; 0: from the shortest)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--tau-max", options->tau_max_s, "fit only taus <= this (s; 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--keep-short-taus", options->keep_short_taus,
                    "do not leave out the shortest taus bent by the sensor's sampling chain "
                    "(filter, decimation)");
  command->add_flag("--exact-model", options->exact_model,
                    "weights and intervals assume the power-law model is exact (no "
                    "model-mismatch scatter, even when chi2 rejects the model)");
  command->add_option("--format", options->format, "json or table")->capture_default_str();
  command->add_option("-o,--output", options->output.path, "write to FILE instead of standard output");
  command->add_flag("--force", options->output.force, "replace existing output files");
  add_spec_export_options(*command, options->spec);
  command->add_flag("--mpi", options->mpi,
                    "under mpirun: each rank reads its own slice of the file and the oadev sums "
                    "are merged in a tree before the fit (docs/scale.md)");
  command->callback([options] { run_fit(*options); });
}

}  // namespace imunoise::cli
