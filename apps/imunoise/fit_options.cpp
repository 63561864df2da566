#include "fit_options.hpp"

#include "imunoise/error.hpp"
#include "imunoise/fit/report.hpp"

namespace imunoise::cli {

void add_fit_options(CLI::App& command, FitOptionsCli& options) {
  command.add_option("--method", options.method,
                     "wls (weighted NNLS, default), ols (the paper's least squares), slope "
                     "(IEEE 952 read-off), gmwm (wavelet moments, several GM terms)")
      ->capture_default_str();
  command.add_option("--terms", options.terms,
                     "terms to fit, comma list of Q,N,B,K,R (R only on request) and the optional "
                     "GM (first-order Gauss-Markov) and SIN (sinusoid), each kept only when the "
                     "data support it (wls); gmwm: GM may repeat (N,K,GM,GM), or auto (WVIC "
                     "selection; the gmwm default)")
      ->capture_default_str();
  command.add_option("--level", options.level, "confidence level of the intervals")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 0.999));
  command.add_option("--selection", options.selection,
                     "wls model selection among the terms: none, aic, bic")
      ->capture_default_str();
  command.add_option("--min-dominant-taus", options.min_dominant_taus,
                     "wls: taus a term must dominate to stay in the fit")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  command.add_flag("--gls", options.gls,
                   "wls: whiten with the full correlation of the overlapping estimates "
                   "(generalised least squares) instead of the diagonal");
  command.add_option("--tau-min", options.tau_min_s, "fit only taus >= this (s; 0: from the shortest)")
      ->check(CLI::NonNegativeNumber);
  command.add_option("--tau-max", options.tau_max_s, "fit only taus <= this (s; 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  command.add_flag("--keep-short-taus", options.keep_short_taus,
                   "do not leave out the shortest taus bent by the sensor's sampling chain "
                   "(filter, decimation)");
  command.add_flag("--exact-model", options.exact_model,
                   "weights and intervals assume the power-law model is exact (no "
                   "model-mismatch scatter, even when chi2 rejects the model)");
  command.add_option("--bootstrap", options.bootstrap,
                     "gmwm: parametric-bootstrap replicates for the intervals (0: delta method only)")
      ->check(CLI::Range(0, 100000));
  command.add_option("--seed", options.seed, "gmwm: seed of the bootstrap")->capture_default_str();
  command.add_flag("--robust", options.robust,
                   "gmwm: robust GMWM for records with outliers (Tukey-biweight wavelet variances, "
                   "60 % Gaussian efficiency; docs/fit.md)");
  command.add_flag("--no-auto-terms", options.no_auto_terms,
                   "wls: do not try the Gauss-Markov and sinusoid terms automatically when chi2 "
                   "rejects the power-law model and the curve has a bump");
}

fit::FitOptions to_fit_options(const FitOptionsCli& options) {
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
  fo.auto_extra_terms = !options.no_auto_terms;
  if (fo.method == fit::Method::gmwm) {
    fo.gmwm.bootstrap = options.bootstrap;
    fo.gmwm.seed = options.seed;
    fo.gmwm.robust = options.robust;
  } else if (options.bootstrap > 0) {
    throw InputError("--bootstrap needs --method gmwm");
  } else if (options.robust) {
    throw InputError("--robust needs --method gmwm (the robust estimator is the robust GMWM); fix: add "
                     "--method gmwm, or drop --robust");
  }
  // --terms keeps its wls default text when not given: gmwm then selects by WVIC.
  fit::parse_method_terms(options.terms, fo);
  std::string why;
  if (!fo.IsValid(&why)) throw InputError("fit options: " + why);
  return fo;
}

}  // namespace imunoise::cli
