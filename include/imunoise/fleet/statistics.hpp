#pragma once
// Distribution summaries of one coefficient over a fleet of sensors, and the robust outlier
// score. Pure functions over spans; no units (the caller keeps them).
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::fleet {

/// The 5 %, 25 %, 50 %, 75 % and 95 % points of a sample.
struct Quantiles {
  std::size_t n = 0;
  double p05 = 0.0, q25 = 0.0, median = 0.0, q75 = 0.0, p95 = 0.0;
};

/// Quantile p (0..1) of ascending `sorted` values by linear interpolation between order
/// statistics: h = (n - 1) p, x[floor h] + (h - floor h)(x[floor h + 1] - x[floor h])
/// (Hyndman & Fan's type 7, NumPy's and R's default). InputError when empty.
double quantile(std::span<const double> sorted, double p);

/// Quantiles of `values` (any order). InputError when empty or not all finite.
Quantiles quantiles(std::span<const double> values);

/// Robust z-scores (Iglewicz & Hoaglin 1993): z_i = 0.6745 (x_i - median) / MAD, MAD the median
/// absolute deviation (0.6745 makes z a standard normal deviate for normal data). When more
/// than half the values are equal (MAD = 0) the mean absolute deviation times sqrt(pi/2)
/// replaces 1.4826 MAD; when every value is equal all z are 0.
std::vector<double> robust_z(std::span<const double> values);

}  // namespace imunoise::fleet
