#include "imunoise/fit/report.hpp"

#include <algorithm>
#include <cmath>

#include "imunoise/error.hpp"

namespace imunoise::fit {
namespace {

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// Eqs. 1-2 exist only with both N and K: 0 from the fit means "not available".
nlohmann::json positive(double v) { return v > 0.0 ? number(v) : nlohmann::json(nullptr); }

/// {value, unit, ci_low, ci_high} of c in a customary gyro unit.
nlohmann::json customary_json(const Coefficient& c, const CustomaryUnit& cu) {
  return {{"value", number(c.value / cu.to_si)}, {"unit", cu.name},
          {"ci_low", number(c.ci_low / cu.to_si)}, {"ci_high", number(c.ci_high / cu.to_si)}};
}

nlohmann::json coefficient_json(const Coefficient& c, double to_unit, const std::string& unit) {
  nlohmann::json j{{"value", number(c.value / to_unit)}, {"unit", unit},
                   {"ci_low", number(c.ci_low / to_unit)}, {"ci_high", number(c.ci_high / to_unit)},
                   {"identified", c.identified}};
  if (!c.note.empty()) j["note"] = c.note;
  return j;
}

nlohmann::json test_json(const ExtraTermTest& t, const FitSummary& summary) {
  // Not tested at all when the power-law fit itself stopped early.
  const std::string verdict =
      t.verdict.empty() ? "not tested: " + summary.message : t.verdict;
  nlohmann::json j{{"selected", t.selected}, {"delta_chi2", number(t.delta_chi2)},
                   {"bic_penalty", number(t.penalty)}, {"dominant_taus", t.dominant_taus},
                   {"verdict", verdict}};
  if (t.tau_max_s > 0) j["dominates_tau_s"] = {t.tau_min_s, t.tau_max_s};
  return j;
}

/// A rate-like coefficient in the record's unit (and deg/h for a gyro).
nlohmann::json rate_json(const RecordInfo& record, const Coefficient& c) {
  nlohmann::json j = coefficient_json(c, record.rate_unit.to_si, record.unit_label);
  if (record.gyro) {
    j["customary"] = customary_json(c, customary_gyro_B);  // a rate: deg/h
  }
  return j;
}

/// One Gauss-Markov term: {sigma, correlation_time_s}.
nlohmann::json gauss_markov_json(const RecordInfo& record, const GaussMarkovTerm& g) {
  return {{"sigma", rate_json(record, g.sigma)},
          {"correlation_time_s", coefficient_json(g.correlation_time_s, 1.0, "s")}};
}

/// "GM" [{sigma, correlation_time_s, fitted, test}] (a list of one: the wls fit has one
/// Gauss-Markov term) and "SIN" {amplitude, frequency_hz, test}.
void add_extra_terms(const RecordInfo& record, const FitOptions& options, const FitResult& r,
                     nlohmann::json& terms) {
  const bool automatic = r.extras.automatic;
  if (options.gauss_markov || automatic) {
    nlohmann::json gm{{"fitted", true}, {"test", test_json(r.extras.gauss_markov, r.summary)}};
    if (automatic) gm["automatic"] = r.extras.reason;
    if (!r.coefficients.gauss_markov.empty()) gm.update(gauss_markov_json(record, r.coefficients.gauss_markov.front()));
    terms["GM"] = nlohmann::json::array({std::move(gm)});
  }
  if (options.sinusoid || automatic) {
    nlohmann::json sin{{"fitted", true}, {"test", test_json(r.extras.sinusoid, r.summary)}};
    if (automatic) sin["automatic"] = r.extras.reason;
    if (r.coefficients.sinusoid) {
      sin["amplitude"] = rate_json(record, r.coefficients.sinusoid->amplitude);
      sin["frequency_hz"] = coefficient_json(r.coefficients.sinusoid->frequency_hz, 1.0, "Hz");
    }
    terms["SIN"] = std::move(sin);
  }
}

/// The "gmwm" section: the fitted model with every term (GM terms as a list by correlation
/// time), the J test, WVIC, the candidates' table and the wavelet variances; record units.
nlohmann::json gmwm_json(const RecordInfo& record, const GmwmResult& g) {
  const double f = record.rate_unit.to_si;
  const auto names = coefficient_units(record.unit_label);
  auto with_boot = [&](nlohmann::json j, double lo, double hi, double to_unit) {
    if (std::isfinite(lo) && std::isfinite(hi)) j["bootstrap_ci"] = {number(lo / to_unit), number(hi / to_unit)};
    return j;
  };
  nlohmann::json terms = nlohmann::json::array();
  nlohmann::json gm = nlohmann::json::array();
  for (const auto& t : g.terms) {
    nlohmann::json j;
    switch (t.kind) {
      case GmwmTerm::GM:
        j["sigma"] = with_boot(coefficient_json(t.magnitude, f, record.unit_label), t.magnitude_boot_low,
                               t.magnitude_boot_high, f);
        j["correlation_time_s"] = with_boot(coefficient_json(t.shape, 1.0, "s"), t.shape_boot_low, t.shape_boot_high, 1.0);
        gm.push_back(j);
        break;
      case GmwmTerm::SIN:
        j["amplitude"] = with_boot(coefficient_json(t.magnitude, f, record.unit_label), t.magnitude_boot_low,
                                   t.magnitude_boot_high, f);
        j["frequency_hz"] = with_boot(coefficient_json(t.shape, 1.0, "Hz"), t.shape_boot_low, t.shape_boot_high, 1.0);
        break;
      case GmwmTerm::BGM: {
        // B like the power-law model's, and the Gauss-Markov states it stands for.
        j = with_boot(coefficient_json(t.magnitude, f, names[static_cast<std::size_t>(kB)]), t.magnitude_boot_low, t.magnitude_boot_high, f);
        nlohmann::json states = nlohmann::json::array();
        for (const auto& s : t.states) states.push_back(gauss_markov_json(record, s));
        j["states"] = std::move(states);
        break;
      }
      default: {
        const int idx = t.kind == GmwmTerm::Q ? kQ : t.kind == GmwmTerm::N ? kN : t.kind == GmwmTerm::B ? kB
                        : t.kind == GmwmTerm::K ? kK : kR;
        j = with_boot(coefficient_json(t.magnitude, f, names[static_cast<std::size_t>(idx)]), t.magnitude_boot_low,
                      t.magnitude_boot_high, f);
      }
    }
    j["term"] = gmwm_term_name(t.kind);
    terms.push_back(std::move(j));
  }
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : g.candidates) {
    candidates.push_back({{"model", c.model}, {"parameters", c.parameters}, {"objective", number(c.objective)},
                          {"j_statistic", number(c.j_statistic)},
                          {"dof", c.dof}, {"j_p_value", number(c.j_p_value)}, {"penalty", number(c.penalty)},
                          {"wvic", number(c.wvic)}, {"converged", c.converged}, {"selected", c.selected}});
  }
  nlohmann::json wv = nlohmann::json::array();
  for (const auto& s : g.scales) {
    wv.push_back({{"tau_s", s.tau_s}, {"wv", number(s.wv / (f * f))}, {"wv_model", number(s.wv_model / (f * f))},
                  {"wv_sd", number(s.wv_sd / (f * f))}});
  }
  nlohmann::json doc = {{"model", g.model},
          {"status", gmwm_status_name(g.status)},
          {"message", g.message},
          {"terms", std::move(terms)},
          {"GM", std::move(gm)},
          {"objective", number(g.objective)},
          {"j_statistic", number(g.j_statistic)},
          {"dof", g.dof},
          {"j_p_value", number(g.j_p_value)},
          {"wvic", number(g.wvic)},
          {"candidates", std::move(candidates)},
          {"bootstrap", {{"replicates", g.bootstrap_replicates}, {"seed", g.seed}}},
          {"wavelet_variance_unit", record.unit_label + "^2"},
          {"wavelet_variance", std::move(wv)},
          {"note", "Haar wavelet variance = overlapping Allan variance / 2 at the dyadic taus; GM terms are "
                   "AR1 processes of the samples, ordered by correlation time; intervals: delta method on "
                   "the log scale (bootstrap_ci: parametric bootstrap percentiles)"}};
  doc["robust"] = g.robust;
  if (g.robust) {
    doc["robust_estimator"] = {
        {"efficiency", g.robust_efficiency},
        {"tuning_constant", g.robust_tuning},
        {"note", "wavelet variances: Tukey-biweight M-estimates of the scale of the Haar coefficients, "
                 "Fisher-consistent at the Gaussian; their covariance: the analytic one / efficiency"}};
  }
  if (!g.flicker_mixture.empty()) {
    const auto& mix = g.flicker_mixture;
    doc["flicker_mixture"] = {
        {"states", mix.correlation_time_s.size()},
        {"per_decade", mix.per_decade},
        {"ripple", mix.ripple},
        {"flat_tau_s", {static_cast<double>(mix.m_lo) / record.rate_hz, static_cast<double>(mix.m_hi) / record.rate_hz}},
        {"correlation_time_s", mix.correlation_time_s},
        {"variance_per_b2", mix.variance_per_b2},
        {"note", "BGM: flicker B as a fixed sum of AR1 states, T_c per_decade per decade, variance ratios "
                 "such that the sum's Allan variance is (2 ln 2 / pi) B^2 over flat_tau_s to the relative "
                 "ripple"}};
  }
  return doc;
}

}  // namespace

void parse_terms(std::string_view list, FitOptions& options) {
  for (bool& t : options.terms) t = false;
  options.gauss_markov = options.sinusoid = false;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view name = list.substr(start, comma - start);
    bool found = false;
    if (name == "GM") options.gauss_markov = found = true;
    if (name == "SIN") options.sinusoid = found = true;
    for (int j = 0; j < kTermCount; ++j) {
      if (name == term_name(j)) {
        options.terms[j] = true;
        found = true;
      }
    }
    if (!found) {
      throw InputError("--terms: unknown term '" + std::string(name) +
                       "'; use a comma list of Q,N,B,K,R and the optional GM (Gauss-Markov) and "
                       "SIN (sinusoid)");
    }
    start = comma + 1;
  }
}

void parse_method_terms(std::string_view list, FitOptions& options) {
  if (options.method == Method::gmwm) {
    parse_gmwm_terms(list == kDefaultTerms ? std::string_view("auto") : list, options.gmwm);
  } else {
    parse_terms(list, options);
  }
}

Selection parse_selection(std::string_view name) {
  if (name == "none") return Selection::none;
  if (name == "aic") return Selection::aic;
  if (name == "bic") return Selection::bic;
  throw InputError("unknown --selection '" + std::string(name) + "'; use none, aic or bic");
}

std::vector<std::string> coefficient_units(const std::string& rate) {
  const bool per_s = rate.size() > 2 && rate.compare(rate.size() - 2, 2, "/s") == 0;
  if (per_s) {
    const std::string base = rate.substr(0, rate.size() - 2);
    return {base, base + "/sqrt(s)", rate, rate + "/sqrt(s)", base + "/s^2"};
  }
  return {rate + "*s", rate + "*sqrt(s)", rate, rate + "/sqrt(s)", rate + "/s"};
}

const CustomaryUnit& customary_unit(int term) {
  static const CustomaryUnit* units[kTermCount] = {&customary_gyro_Q, &customary_gyro_N,
                                                   &customary_gyro_B, &customary_gyro_K,
                                                   &customary_gyro_R};
  return *units[term];
}

nlohmann::json report_json(const RecordInfo& record, const FitOptions& options,
                           const FitResult& r) {
  const double f = record.rate_unit.to_si;
  const auto names = coefficient_units(record.unit_label);
  nlohmann::json terms = nlohmann::json::object();
  for (int j = 0; j < kTermCount; ++j) {
    const auto& c = coefficient(r.coefficients, j);
    nlohmann::json t{{"value", number(c.value / f)}, {"unit", names[static_cast<std::size_t>(j)]},
                     {"ci_low", number(c.ci_low / f)}, {"ci_high", number(c.ci_high / f)},
                     {"identified", c.identified}, {"fitted", r.terms[j].fitted},
                     {"estimate", number(r.terms[j].estimate / f)}};
    if (!c.note.empty()) t["note"] = c.note;
    if (r.terms[j].tau_max_s > 0) {
      t["dominates_tau_s"] = {r.terms[j].tau_min_s, r.terms[j].tau_max_s};
    }
    if (record.gyro) {
      t["customary"] = customary_json(c, customary_unit(j));
    }
    terms[term_name(j)] = std::move(t);
  }
  if (options.gauss_markov || options.sinusoid || r.extras.automatic) {
    add_extra_terms(record, options, r, terms);
  }
  if (r.gmwm) {
    // Every GM term of the gmwm model, by correlation time, in the same shape as the wls one's;
    // the bootstrap intervals are in the "gmwm" section.
    nlohmann::json gm = nlohmann::json::array();
    const auto& mix = r.gmwm->flicker_mixture.correlation_time_s;
    for (const auto& g : r.coefficients.gauss_markov) {
      nlohmann::json j = gauss_markov_json(record, g);
      j["fitted"] = true;
      // A state of the flicker mixture (its T_c is fixed, not estimated).
      if (std::find(mix.begin(), mix.end(), g.correlation_time_s.value) != mix.end() &&
          g.correlation_time_s.ci_low == g.correlation_time_s.ci_high) {
        j["part_of"] = "BGM";
      }
      gm.push_back(std::move(j));
    }
    if (!gm.empty()) terms["GM"] = std::move(gm);
    if (const auto& s = r.coefficients.sinusoid) {
      terms["SIN"] = {{"fitted", true}, {"amplitude", rate_json(record, s->amplitude)},
                      {"frequency_hz", coefficient_json(s->frequency_hz, 1.0, "Hz")}};
    }
  }
  const auto& s = r.summary;
  nlohmann::json residuals = nlohmann::json::array();
  for (const auto& p : r.residuals) {
    residuals.push_back({{"tau_s", p.tau_s}, {"adev", number(std::sqrt(p.avar) / f)},
                         {"adev_model", number(std::sqrt(p.avar_model) / f)},
                         {"normalized_residual", number(p.normalized)},
                         {"dominant_term", p.dominant_term >= 0
                                               ? nlohmann::json(term_name(p.dominant_term))
                                               : nlohmann::json(nullptr)},
                         {"used", p.used}});
  }
  nlohmann::json excluded = nlohmann::json::array();
  for (const auto& e : s.excluded_taus) excluded.push_back({{"tau_s", e.tau_s}, {"reason", e.reason}});
  nlohmann::json doc = {
      {"unit", record.unit_label},
      {"method", method_name(options.method)},
      {"level", options.level},
      {"source", record.source},
      {"rate_hz", record.rate_hz},
      {"n_samples", record.n_samples},
      {"terms", std::move(terms)},
      {"paper", {{"tau_opt_s", positive(r.tau_opt_s)},
                 {"adev_min_eq2", positive(std::sqrt(r.avar_min_eq2) / f)},
                 {"adev_min_measured", number(std::sqrt(r.avar_min_measured) / f)},
                 {"tau_min_measured_s", number(r.tau_min_measured_s)},
                 {"note", "eqs. 1-2 use the fitted N and K only (white noise + rate random walk; "
                          "null when either is not identified); the measured minimum includes "
                          "every term"}}},
      {"diagnostics", {{"termination", termination_name(s.termination)},
                       {"message", s.message},
                       {"iterations", s.iterations},
                       {"taus_used", s.points_used},
                       {"chi2", number(s.chi2)},
                       {"dof", s.dof},
                       {"chi2_dof", number(s.chi2_dof)},
                       {"mismatch_scatter", number(s.mismatch_scatter)},
                       {"chi2_dof_with_mismatch", number(s.chi2_dof_with_mismatch)},
                       {"excluded_taus", std::move(excluded)},
                       {"warnings", s.warnings},
                       {"residuals", std::move(residuals)}}}};
  if (r.gmwm) doc["gmwm"] = gmwm_json(record, *r.gmwm);
  return doc;
}

}  // namespace imunoise::fit
