#pragma once
// The command-line binding of the noise-model fit's options (imunoise/fit/fit.hpp): one binder
// for every subcommand that fits (fit, analyze, fleet), so each accepts the same options.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include "imunoise/fit/fit.hpp"

namespace imunoise::cli {

struct FitOptionsCli {
  std::string method = "wls";
  std::string terms = "Q,N,B,K";
  std::string selection = "none";
  double level = 0.95;
  int min_dominant_taus = 2;
  bool gls = false;
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  bool keep_short_taus = false;
  bool exact_model = false;
  bool no_auto_terms = false;
  int bootstrap = 0;       ///< gmwm: parametric bootstrap replicates
  std::uint64_t seed = 1;  ///< gmwm: bootstrap seed
  bool robust = false;     ///< gmwm: robust (bounded-influence) wavelet variances
};

/// Registers --method --terms --level --selection --min-dominant-taus --gls --tau-min
/// --tau-max --keep-short-taus --exact-model --no-auto-terms on `command`.
void add_fit_options(CLI::App& command, FitOptionsCli& options);

/// The library's fit options; InputError when they are inconsistent.
fit::FitOptions to_fit_options(const FitOptionsCli& options);

}  // namespace imunoise::cli
