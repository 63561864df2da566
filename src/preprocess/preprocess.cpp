#include "imunoise/preprocess/preprocess.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "imunoise/allan.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/preprocess/pooled_deviation.hpp"

namespace imunoise::preprocess {

DetrendOrder parse_detrend(std::string_view text) {
  if (text == "none") return DetrendOrder::none;
  if (text == "linear") return DetrendOrder::linear;
  if (text == "quadratic") return DetrendOrder::quadratic;
  throw InputError("--detrend " + std::string(text) + " is not known; fix: pass none, linear or quadratic");
}

DetrendReport detrend(std::span<double> values, double rate_hz, DetrendOrder order) {
  DetrendReport report;
  report.order = order;
  const std::size_t n = values.size();
  const int degree = static_cast<int>(order);
  if (order == DetrendOrder::none || n < static_cast<std::size_t>(degree) + 2) return report;
  // Least squares in the scaled variable u = (2 i - (n - 1)) / (n - 1) in [-1, 1] (well
  // conditioned normal equations), then converted to powers of t = i / rate.
  const double half = static_cast<double>(n - 1) / 2.0;
  std::array<double, 5> su{};   // sum u^k, k = 0..4
  std::array<double, 3> sy{};   // sum y u^k
  for (std::size_t i = 0; i < n; ++i) {
    const double u = (static_cast<double>(i) - half) / half;
    double p = 1.0;
    for (int k = 0; k <= 2 * degree; ++k) {
      su[static_cast<std::size_t>(k)] += p;
      if (k <= degree) sy[static_cast<std::size_t>(k)] += values[i] * p;
      p *= u;
    }
  }
  // Solve the (degree+1)^2 normal equations by Gaussian elimination with partial pivoting.
  const int d = degree + 1;
  double a[3][4] = {};
  for (int r = 0; r < d; ++r) {
    for (int c = 0; c < d; ++c) a[r][c] = su[static_cast<std::size_t>(r + c)];
    a[r][d] = sy[static_cast<std::size_t>(r)];
  }
  for (int c = 0; c < d; ++c) {
    int pivot = c;
    for (int r = c + 1; r < d; ++r) if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    for (int k = 0; k <= d; ++k) std::swap(a[c][k], a[pivot][k]);
    for (int r = 0; r < d; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (int k = c; k <= d; ++k) a[r][k] -= f * a[c][k];
    }
  }
  double b[3] = {0, 0, 0};  // coefficients in u
  for (int r = 0; r < d; ++r) b[r] = a[r][d] / a[r][r];
  // u = (t * rate - half) / half = alpha t + beta.
  const double alpha = rate_hz / half;
  const double beta = -1.0;
  report.coefficients.assign(static_cast<std::size_t>(d), 0.0);
  auto& c = report.coefficients;
  c[0] = b[0] + b[1] * beta + (degree == 2 ? b[2] * beta * beta : 0.0);
  if (d > 1) c[1] = b[1] * alpha + (degree == 2 ? 2.0 * b[2] * alpha * beta : 0.0);
  if (d > 2) c[2] = b[2] * alpha * alpha;
  double mean = 0.0;
  double sq = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = (static_cast<double>(i) - half) / half;
    const double fit = b[0] + u * (b[1] + (degree == 2 ? u * b[2] : 0.0));
    values[i] -= fit;
    const double centred = fit - b[0];
    mean += centred;
    sq += centred * centred;
  }
  mean /= static_cast<double>(n);
  report.removed_rms = std::sqrt(std::max(0.0, sq / static_cast<double>(n) - mean * mean));
  return report;
}

double default_spike_threshold(std::size_t n) {
  // Solve n * erfc(z / sqrt 2) = 0.01 for z by bisection (erfc is monotone).
  const double target = 0.01 / static_cast<double>(std::max<std::size_t>(n, 1));
  double lo = 0.0;
  double hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::numbers::sqrt2) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {
double median_of(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  double m = *mid;
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
  return m;
}
}  // namespace

OutlierReport find_spikes(std::span<const double> values, double threshold, std::string_view source) {
  OutlierReport report;
  if (values.empty()) return report;
  std::vector<double> work(values.begin(), values.end());
  report.median = median_of(work);
  for (std::size_t i = 0; i < values.size(); ++i) work[i] = std::abs(values[i] - report.median);
  // 1.4826 = 1 / Phi^-1(3/4): the MAD of a Gaussian is 0.6745 sigma.
  report.robust_sigma = 1.482602218505602 * median_of(work);
  report.threshold_sigmas = threshold > 0.0 ? threshold : default_spike_threshold(values.size());
  if (report.robust_sigma == 0.0) {
    // More than half the samples are equal (quantised, or a stuck sensor): a MAD test cannot
    // tell spikes from noise.
    throw InputError(std::string(source) + ": more than half of the samples equal the median, so spikes "
                     "cannot be told from noise by the median absolute deviation; fix: pass --outliers "
                     "report only on records with noise above the quantisation step, or omit --outliers");
  }
  const double limit = report.threshold_sigmas * report.robust_sigma;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::abs(values[i] - report.median) > limit) report.indices.push_back(i);
  }
  return report;
}

std::vector<Segment> split_segments(std::size_t n, std::span<const std::size_t> breaks,
                                    std::span<const std::size_t> removed) {
  std::vector<std::size_t> cuts(breaks.begin(), breaks.end());
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::size_t> drop(removed.begin(), removed.end());
  std::sort(drop.begin(), drop.end());
  std::vector<Segment> out;
  std::size_t begin = 0;
  std::size_t c = 0;
  std::size_t r = 0;
  for (std::size_t i = 0; i <= n; ++i) {
    const bool at_cut = c < cuts.size() && cuts[c] == i;
    const bool at_drop = r < drop.size() && drop[r] == i;
    if (i == n || at_cut || at_drop) {
      if (i > begin) out.push_back({begin, i});
      begin = at_drop ? i + 1 : i;
    }
    while (c < cuts.size() && cuts[c] <= i) ++c;
    while (r < drop.size() && drop[r] <= i) ++r;
  }
  return out;
}

std::vector<DevPoint> pooled_oadev(std::span<const double> rate_si, std::span<const Segment> segments,
                                   double tau0_s, std::span<const std::size_t> factors, double level) {
  PoolOptions options;
  options.level = level;
  return pooled_deviation(Estimator::oadev, rate_si, segments, tau0_s, factors, options).points;
}

}  // namespace imunoise::preprocess
