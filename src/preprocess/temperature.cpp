#include "imunoise/preprocess/temperature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/preprocess/preprocess.hpp"

namespace imunoise::preprocess {

std::vector<TemperatureBin> temperature_bins(std::span<const double> rate_si, std::span<const double> temperature,
                                             double rate_hz, double bin_width, std::size_t min_samples,
                                             const fit::FitOptions* fit_options,
                                             std::span<const std::size_t> breaks) {
  if (!(bin_width > 0.0) || !std::isfinite(bin_width)) {
    throw InputError("temperature bin width must be positive, got " + fmt::format("{:g}", bin_width) +
                     "; fix: pass e.g. --temperature-bin 5");
  }
  if (rate_si.size() != temperature.size()) {
    throw InputError("the temperature channel has " + std::to_string(temperature.size()) + " samples but the rate " +
                     std::to_string(rate_si.size()) + "; fix: give a temperature for every sample");
  }
  // Runs of consecutive samples in the same bin (and not across a break), grouped by bin.
  std::vector<std::size_t> cuts(breaks.begin(), breaks.end());
  std::sort(cuts.begin(), cuts.end());
  std::map<long long, std::vector<Segment>> runs;
  for (std::size_t i = 0; i < temperature.size();) {
    if (!std::isfinite(temperature[i])) {
      throw InputError("temperature sample " + std::to_string(i) + " is not finite; fix: repair the temperature channel");
    }
    const auto bin = static_cast<long long>(std::floor(temperature[i] / bin_width));
    std::size_t j = i + 1;
    while (j < temperature.size() && std::isfinite(temperature[j]) &&
           static_cast<long long>(std::floor(temperature[j] / bin_width)) == bin &&
           !std::binary_search(cuts.begin(), cuts.end(), j)) {
      ++j;
    }
    runs[bin].push_back({i, j});
    i = j;
  }
  const double tau0 = 1.0 / rate_hz;
  std::vector<TemperatureBin> out;
  for (const auto& [bin, segments] : runs) {
    TemperatureBin b;
    b.low = static_cast<double>(bin) * bin_width;
    b.high = b.low + bin_width;
    b.segments = segments.size();
    long double sum = 0.0L;
    long double sum_t = 0.0L;
    for (const auto& s : segments) {
      b.samples += s.size();
      for (std::size_t i = s.begin; i < s.end; ++i) {
        sum += rate_si[i];
        sum_t += temperature[i];
      }
    }
    if (b.samples < min_samples) continue;
    b.bias_si = static_cast<double>(sum / static_cast<long double>(b.samples));
    b.mean_temperature = static_cast<double>(sum_t / static_cast<long double>(b.samples));
    long double sq = 0.0L;
    for (const auto& s : segments) {
      for (std::size_t i = s.begin; i < s.end; ++i) sq += (rate_si[i] - b.bias_si) * (rate_si[i] - b.bias_si);
    }
    b.bias_stderr_si = static_cast<double>(std::sqrt(sq / static_cast<long double>(b.samples - 1))) /
                       std::sqrt(static_cast<double>(b.samples));
    std::size_t longest = 0;
    for (const auto& s : segments) longest = std::max(longest, s.size());
    std::vector<std::size_t> factors;
    for (std::size_t m = 1; 2 * m + 1 <= longest + 1; m *= 2) factors.push_back(m);
    b.oadev = pooled_oadev(rate_si, segments, tau0, factors);
    b.random_walk_si = std::numeric_limits<double>::quiet_NaN();
    b.bias_instability_si = std::numeric_limits<double>::quiet_NaN();
    double best = std::numeric_limits<double>::infinity();
    double minimum = std::numeric_limits<double>::infinity();
    for (const auto& p : b.oadev) {
      const double distance = std::abs(std::log(p.tau_s));
      if (distance < best) {
        best = distance;
        b.random_walk_si = p.dev * std::sqrt(p.tau_s);
        b.random_walk_tau_s = p.tau_s;
      }
      minimum = std::min(minimum, p.dev);
    }
    // 0.664 = sqrt(2 ln 2 / pi): the flat floor of the Allan deviation of flicker rate noise.
    if (std::isfinite(minimum)) b.bias_instability_si = minimum / 0.664;
    if (fit_options != nullptr) {
      // The bin's runs pooled (no term spans two runs); the covariance of one record of their
      // summed length, as for a record split at gaps (study/fit_stage.hpp).
      std::size_t n_phase = 0;
      for (const auto& s : segments) n_phase += s.size() + 1;
      fit::FitResult r = fit::fit_allan(b.oadev, n_phase, tau0, *fit_options);
      if (r.summary.termination == fit::Termination::degenerate_input ||
          r.summary.termination == fit::Termination::too_few_points) {
        b.fit_error = "cannot fit a noise model: " + r.summary.message;
      } else {
        if (segments.size() > 1) {
          r.summary.warnings.insert(r.summary.warnings.begin(),
                                    "fitted to the oadev pooled over the bin's " + std::to_string(segments.size()) +
                                    " runs, with the estimate covariance of one record of their summed length");
        }
        b.fit = std::move(r);
      }
    }
    out.push_back(std::move(b));
  }
  return out;
}

namespace {

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string bin_name(const TemperatureBin& b) {
  return fmt::format("temperature [{:g}, {:g})", b.low, b.high);
}

}  // namespace

nlohmann::json temperature_bins_json(const std::vector<TemperatureBin>& bins, const fit::RecordInfo& record,
                                     const fit::FitOptions& options) {
  auto out = nlohmann::json::array();
  for (const auto& b : bins) {
    nlohmann::json j{{"low", b.low}, {"high", b.high}, {"samples", b.samples}, {"runs", b.segments},
                     {"mean_temperature", b.mean_temperature}, {"bias_si", b.bias_si},
                     {"bias_stderr_si", b.bias_stderr_si}, {"N_si", json_number(b.random_walk_si)},
                     {"N_tau_s", b.random_walk_tau_s}, {"B_si", json_number(b.bias_instability_si)}};
    if (b.fit) {
      fit::RecordInfo info = record;
      info.source = record.source + " " + bin_name(b);
      info.n_samples = b.samples;
      j["fit"] = fit::report_json(info, options, *b.fit);
    } else if (!b.fit_error.empty()) {
      j["fit_error"] = b.fit_error;
    }
    out.push_back(std::move(j));
  }
  return out;
}

std::vector<std::string> temperature_bins_lines(const std::vector<TemperatureBin>& bins,
                                                const fit::RecordInfo& record) {
  const double f = record.rate_unit.to_si;
  const auto units = fit::coefficient_units(record.unit_label);
  auto cell = [](double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : std::string("-"); };
  std::vector<std::string> lines;
  for (const auto& b : bins) {
    std::string line = fmt::format("{}: {} samples in {} runs, mean {:.4g}; bias {:.6g} +- {:.2g} {}", bin_name(b),
                                   b.samples, b.segments, b.mean_temperature, b.bias_si / f, b.bias_stderr_si / f,
                                   record.unit_label);
    if (b.fit) {
      for (int t = 0; t < 4; ++t) {
        const auto& c = fit::coefficient(b.fit->coefficients, t);
        line += fmt::format("; {} ", fit::term_name(t));
        line += c.identified ? fmt::format("{} [{}, {}] {}", cell(c.value / f), cell(c.ci_low / f),
                                           cell(c.ci_high / f), units[static_cast<std::size_t>(t)])
                             : std::string("-");
      }
      line += fmt::format("; fit {}, chi2/dof {:.3g}", fit::termination_name(b.fit->summary.termination),
                          b.fit->summary.chi2_dof);
    } else if (!b.fit_error.empty()) {
      line += "; " + b.fit_error;
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace imunoise::preprocess
