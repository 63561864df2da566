#include "imunoise/preprocess/dynamic_allan.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/core.h>

#include "imunoise/allan.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"

namespace imunoise::preprocess {

DavarResult dynamic_allan(std::span<const double> rate_si, double rate_hz, const DavarOptions& options) {
  const std::size_t n = rate_si.size();
  const double duration_s = static_cast<double>(n) / rate_hz;
  DavarResult r;
  r.window_s = options.window_s > 0.0 ? options.window_s : duration_s / 10.0;
  r.step_s = options.step_s > 0.0 ? options.step_s : r.window_s / 2.0;
  const auto window = static_cast<std::size_t>(std::llround(r.window_s * rate_hz));
  const auto step = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(r.step_s * rate_hz)));
  if (window < 100 || window > n || n - window < step) {
    throw InputError("dynamic Allan variance: a window of " + fmt::format("{:g}", r.window_s) + " s (" +
                     std::to_string(window) + " samples) needs at least two windows of >= 100 samples in a record of " +
                     std::to_string(n) + " samples; fix: choose a shorter window");
  }
  // Octave factors with at least 10 terms per window (edf >= ~10: the band stays meaningful).
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; window / m >= 10 && 2 * m + 1 <= window + 1; m *= 2) factors.push_back(m);
  const double tau0 = 1.0 / rate_hz;
  for (const auto m : factors) r.tau_s.push_back(static_cast<double>(m) * tau0);
  for (std::size_t start = 0; start + window <= n; start += step) {
    const auto part = rate_si.subspan(start, window);
    const auto phase = phase_from_rate(part, tau0, compensated_mean(part));
    const auto points = oadev(phase, tau0, factors);
    std::vector<double> avar;
    for (const auto& p : points) avar.push_back(p.dev * p.dev);
    r.window_start_s.push_back(static_cast<double>(start) * tau0);
    r.avar.push_back(std::move(avar));
  }
  const std::size_t windows = r.avar.size();
  const double p = 0.001 / static_cast<double>(windows * factors.size());
  r.flagged.assign(windows, std::vector<bool>(factors.size(), false));
  r.window_flagged.assign(windows, false);
  for (std::size_t j = 0; j < factors.size(); ++j) {
    std::vector<double> column;
    for (const auto& w : r.avar) column.push_back(w[j]);
    auto mid = column.begin() + static_cast<std::ptrdiff_t>(windows / 2);
    std::nth_element(column.begin(), mid, column.end());
    r.reference_avar.push_back(*mid);
    const double edf = static_cast<double>(window + 1) / static_cast<double>(factors[j]) - 1.0;
    const double low = chi2_quantile(p / 2.0, edf) / edf;
    const double high = chi2_quantile(1.0 - p / 2.0, edf) / edf;
    for (std::size_t w = 0; w < windows; ++w) {
      const double ratio = r.avar[w][j] / r.reference_avar[j];
      if (!(ratio >= low && ratio <= high)) {
        r.flagged[w][j] = true;
        r.window_flagged[w] = true;
      }
    }
  }
  r.stationary = std::none_of(r.window_flagged.begin(), r.window_flagged.end(), [](bool f) { return f; });
  if (r.window_flagged.front()) {
    std::size_t w = 0;
    while (w < windows && r.window_flagged[w]) ++w;
    r.suggested_skip_s = w < windows ? r.window_start_s[w] : 0.0;
  }
  for (std::size_t w = 1; w < windows; ++w) {
    if (r.window_flagged[w] != r.window_flagged[w - 1]) {
      const double centre_prev = r.window_start_s[w - 1] + r.window_s / 2.0;
      const double centre = r.window_start_s[w] + r.window_s / 2.0;
      r.change_times_s.push_back(0.5 * (centre_prev + centre));
    }
  }
  return r;
}

}  // namespace imunoise::preprocess
