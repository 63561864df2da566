#include "imunoise/fleet/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "imunoise/error.hpp"

namespace imunoise::fleet {

double quantile(std::span<const double> sorted, double p) {
  if (sorted.empty()) throw InputError("quantile of an empty sample");
  const double h = static_cast<double>(sorted.size() - 1) * std::clamp(p, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

Quantiles quantiles(std::span<const double> values) {
  std::vector<double> sorted(values.begin(), values.end());
  for (const double v : sorted) {
    if (!std::isfinite(v)) throw InputError("quantiles of a sample with NaN or Inf");
  }
  std::sort(sorted.begin(), sorted.end());
  Quantiles q;
  q.n = sorted.size();
  q.p05 = quantile(sorted, 0.05);
  q.q25 = quantile(sorted, 0.25);
  q.median = quantile(sorted, 0.5);
  q.q75 = quantile(sorted, 0.75);
  q.p95 = quantile(sorted, 0.95);
  return q;
}

std::vector<double> robust_z(std::span<const double> values) {
  std::vector<double> z(values.size(), 0.0);
  if (values.empty()) return z;
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const double median = quantile(sorted, 0.5);
  std::vector<double> deviation(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) deviation[i] = std::abs(values[i] - median);
  std::sort(deviation.begin(), deviation.end());
  const double mad = quantile(deviation, 0.5);
  double scale = 0.0;  // the standard deviation estimate: 1.4826 MAD, or the fallback
  if (mad > 0.0) {
    scale = mad / 0.6745;
  } else {
    double mean_abs = 0.0;
    for (const double d : deviation) mean_abs += d;
    mean_abs /= static_cast<double>(deviation.size());
    scale = mean_abs * std::sqrt(std::numbers::pi / 2.0);
  }
  if (!(scale > 0.0)) return z;
  for (std::size_t i = 0; i < values.size(); ++i) z[i] = (values[i] - median) / scale;
  return z;
}

}  // namespace imunoise::fleet
