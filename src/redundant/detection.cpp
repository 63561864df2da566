#include "imunoise/redundant/detection.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::redundant {

FaultDetector::FaultDetector(const Geometry& geometry, std::span<const SensorModel> sensors,
                             double rate_hz, const DetectionOptions& options) {
  n_ = geometry.size();
  if (!(rate_hz > 0) || !std::isfinite(rate_hz)) {
    throw InputError(fmt::format("fault detection: the sample rate must be positive, got {} Hz", rate_hz));
  }
  if (n_ < 4) {
    throw InputError(fmt::format("fault detection needs at least 4 sensors (geometry {} has {}): "
                                 "with 3 there is no parity space", geometry.name, n_));
  }
  if (sensors.size() != n_) {
    throw InputError(fmt::format("fault detection needs each sensor's noise model (got {} for {} "
                                 "sensors): pass --from FIT.json for every sensor, in order",
                                 sensors.size(), n_));
  }
  std::string why;
  if (!options.IsValid(&why)) throw InputError("fault detection: " + why);
  // Whole samples per block, whole blocks per window, whole windows per reference.
  const auto window_samples =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(options.window_s * rate_hz)));
  const auto blocks = static_cast<std::size_t>(options.blocks_per_window);
  result_.block_samples = std::max<std::size_t>(1, window_samples / blocks);
  blocks_per_window_ = std::max<std::size_t>(1, window_samples / result_.block_samples);
  result_.window_samples = blocks_per_window_ * result_.block_samples;
  result_.reference_windows = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::llround(options.reference_s / (static_cast<double>(result_.window_samples) / rate_hz))));
  DetectionOptions used = options;
  used.window_s = static_cast<double>(result_.window_samples) / rate_hz;
  used.reference_s = used.window_s * static_cast<double>(result_.reference_windows);
  if (!used.IsValid(&why)) throw InputError("fault detection: " + why);
  result_.design = design_detection(geometry, sensors, used);
  result_.rate_hz = rate_hz;
  k_ = result_.design.dof;
  threshold_ = result_.design.threshold;
  exclude_isolated_ = options.exclude_isolated;
  const Matrix& vw = result_.design.whitened_parity;
  vw_ = vw.values;
  for (const double s : result_.design.sigma_difference_rad_s) inv_sigma_.push_back(1.0 / s);
  sigma_ = result_.design.sigma_difference_rad_s;
  axes_ = geometry.axes;
  active_.assign(n_, true);
  update_isolable();
  block_acc_.assign(n_, 0.0);
  blocks_.assign(2 * blocks_per_window_ * n_, 0.0);
  windows_.assign((result_.reference_windows + 1) * n_, 0.0);
}

void FaultDetector::update_isolable() {
  // Isolable: at least 2 parity rows and no zero and no two parallel columns among the sensors
  // still monitored.
  isolable_ = k_ >= 2;
  auto col = [&](std::size_t r, std::size_t i) { return vw_[r * n_ + i]; };
  for (std::size_t i = 0; i < n_ && isolable_; ++i) {
    if (!active_[i]) continue;
    double ii = 0;
    for (std::size_t r = 0; r < k_; ++r) ii += col(r, i) * col(r, i);
    if (ii < 1e-18) isolable_ = false;
    for (std::size_t j = i + 1; j < n_ && isolable_; ++j) {
      if (!active_[j]) continue;
      double ij = 0, jj = 0;
      for (std::size_t r = 0; r < k_; ++r) {
        ij += col(r, i) * col(r, j);
        jj += col(r, j) * col(r, j);
      }
      if (std::abs(ij) > (1.0 - 1e-9) * std::sqrt(ii * jj)) isolable_ = false;
    }
  }
}

void FaultDetector::exclude(std::size_t sensor) {
  // The isolated sensor leaves the test: parity of the others (whitened), one degree of
  // freedom less, threshold at the same per-test probability. Its column becomes zero.
  active_[sensor] = false;
  result_.excluded.push_back(sensor);
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < n_; ++i) if (active_[i]) keep.push_back(i);
  Matrix hw(keep.size(), 3);
  for (std::size_t r = 0; r < keep.size(); ++r) {
    for (std::size_t c = 0; c < 3; ++c) hw(r, c) = axes_[keep[r]][c] / sigma_[keep[r]];
  }
  k_ = keep.size() > 3 ? keep.size() - 3 : 0;
  // The others must still span 3-D (else they have no parity space left to test).
  double m[3][3] = {};
  for (std::size_t r = 0; r < hw.rows; ++r) {
    for (int a = 0; a < 3; ++a) for (int b = 0; b < 3; ++b) m[a][b] += hw(r, static_cast<std::size_t>(a)) * hw(r, static_cast<std::size_t>(b));
  }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  const double trace = m[0][0] + m[1][1] + m[2][2];
  if (!(det > 1e-12 * trace * trace * trace)) k_ = 0;
  vw_.assign(k_ * n_, 0.0);
  if (k_ > 0) {
    const Matrix v = parity_basis(hw);
    for (std::size_t r = 0; r < k_; ++r) {
      for (std::size_t j = 0; j < keep.size(); ++j) vw_[r * n_ + keep[j]] = v(r, j);
    }
    const boost::math::chi_squared_distribution<double> chi2(static_cast<double>(k_));
    threshold_ = boost::math::quantile(boost::math::complement(chi2, result_.design.per_test_probability));
  }
  update_isolable();
}

void FaultDetector::push(std::span<const std::span<const double>> sensors) {
  if (sensors.size() != n_) {
    throw InputError(fmt::format("fault detection: {} sample streams for {} sensors", sensors.size(), n_));
  }
  const std::size_t len = sensors[0].size();
  for (const auto& s : sensors) {
    if (s.size() != len) throw InputError("fault detection: the sensors' chunks differ in length");
  }
  std::size_t t = 0;
  while (t < len) {
    const std::size_t take = std::min(len - t, result_.block_samples - in_block_);
    for (std::size_t i = 0; i < n_; ++i) {
      const double* x = sensors[i].data() + t;
      double acc = 0.0;
#pragma omp simd reduction(+ : acc)
      for (std::size_t u = 0; u < take; ++u) acc += x[u];
      block_acc_[i] += acc;
    }
    in_block_ += take;
    t += take;
    if (in_block_ == result_.block_samples) close_block();
  }
  result_.samples += len;
}

void FaultDetector::close_block() {
  const std::size_t slot = blocks_done_ % (2 * blocks_per_window_);
  std::copy(block_acc_.begin(), block_acc_.end(), blocks_.begin() + static_cast<std::ptrdiff_t>(slot * n_));
  std::fill(block_acc_.begin(), block_acc_.end(), 0.0);
  in_block_ = 0;
  ++blocks_done_;
  if (blocks_done_ % blocks_per_window_ == 0) close_window();
}

void FaultDetector::close_window() {
  // Sum of the window's blocks into the window ring.
  const std::size_t wslot = windows_done_ % (result_.reference_windows + 1);
  double* w = windows_.data() + wslot * n_;
  std::fill(w, w + n_, 0.0);
  for (std::size_t b = 0; b < blocks_per_window_; ++b) {
    const std::size_t slot = (blocks_done_ - 1 - b) % (2 * blocks_per_window_);
    for (std::size_t i = 0; i < n_; ++i) w[i] += blocks_[slot * n_ + i];
  }
  ++windows_done_;
  if (windows_done_ > result_.reference_windows) test();
}

void FaultDetector::test() {
  const std::size_t R = result_.reference_windows;
  const std::size_t ring = R + 1;
  const std::size_t current = (windows_done_ - 1) % ring;
  const double L = static_cast<double>(result_.window_samples);
  const double M = L * static_cast<double>(R);
  std::vector<double> ref(n_, 0.0);
  for (std::size_t w = 1; w <= R; ++w) {
    const std::size_t slot = (windows_done_ - 1 - w) % ring;
    for (std::size_t i = 0; i < n_; ++i) ref[i] += windows_[slot * n_ + i];
  }
  std::vector<double> z(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    z[i] = (windows_[current * n_ + i] / L - ref[i] / M) * inv_sigma_[i];
  }
  std::vector<double> p(k_, 0.0);
  double stat = 0.0;
  for (std::size_t r = 0; r < k_; ++r) {
    for (std::size_t i = 0; i < n_; ++i) p[r] += vw_[r * n_ + i] * z[i];
    stat += p[r] * p[r];
  }
  if (k_ == 0) return;  // every redundant sensor excluded: nothing left to test
  ++result_.tests;
  result_.max_statistic = std::max(result_.max_statistic, stat);
  const std::size_t test_index = result_.tests;
  if (!(stat > threshold_)) return;
  ++result_.alarms;
  // Isolation: the sensor whose parity column best explains p.
  std::size_t best = 0;
  double best_score = -1.0;
  std::vector<double> scores(n_, -1.0);
  for (std::size_t i = 0; i < n_; ++i) {
    if (!active_[i]) continue;
    double dot = 0, norm = 0;
    for (std::size_t r = 0; r < k_; ++r) {
      dot += vw_[r * n_ + i] * p[r];
      norm += vw_[r * n_ + i] * vw_[r * n_ + i];
    }
    scores[i] = norm > 0 ? dot * dot / norm : 0.0;
    if (scores[i] > best_score) {
      best_score = scores[i];
      best = i;
    }
  }
  // Sensors that explain the parity as well as the best (equal in exact arithmetic when their
  // parity columns are parallel: no isolation among them).
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < n_; ++i) {
    if (active_[i] && scores[i] >= (1.0 - 1e-9) * best_score) candidates.push_back(i);
  }
  if (open_ && test_index - last_alarm_test_ <= R + 1 &&
      (!result_.faults.back().isolated || result_.faults.back().sensor == best)) {
    auto& e = result_.faults.back();
    ++e.alarms;
    e.max_statistic = std::max(e.max_statistic, stat);
    last_alarm_test_ = test_index;
    return;
  }
  // Onset: change point of q_b = f . (block sum - nb ref mean) over the last two windows,
  // f = S^-1 Vw^T Vw e_best (the fault direction in the sensors' space). The reference here
  // leaves out the previous window, which may already hold the onset.
  std::vector<double> f(n_, 0.0);
  for (std::size_t i = 0; i < n_; ++i) {
    for (std::size_t r = 0; r < k_; ++r) f[i] += vw_[r * n_ + i] * vw_[r * n_ + best];
    f[i] *= inv_sigma_[i];
  }
  const std::size_t prev = (windows_done_ - 2) % ring;
  const double M2 = M - L;
  std::vector<double> ref2(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    ref2[i] = R > 1 ? (ref[i] - windows_[prev * n_ + i]) / M2 : ref[i] / M;
  }
  const std::size_t nb = 2 * blocks_per_window_;
  const std::size_t available = std::min(nb, blocks_done_);
  std::vector<double> q(available);
  const double bs = static_cast<double>(result_.block_samples);
  for (std::size_t b = 0; b < available; ++b) {
    // b = 0 is the oldest block of the two windows.
    const std::size_t slot = (blocks_done_ - available + b) % nb;
    double v = 0;
    for (std::size_t i = 0; i < n_; ++i) v += f[i] * (blocks_[slot * n_ + i] - bs * ref2[i]);
    q[b] = v;
  }
  std::size_t onset_block = available - 1;
  double best_lr = -1.0, tail = 0.0;
  for (std::size_t b = available; b-- > 0;) {
    tail += q[b];
    const double lr = tail * tail / static_cast<double>(available - b);
    if (lr > best_lr) {
      best_lr = lr;
      onset_block = b;
    }
  }
  const std::size_t first_block = blocks_done_ - available + onset_block;
  FaultEvent e;
  e.sensor = best;
  e.candidates = isolable_ ? std::vector<std::size_t>{best} : std::move(candidates);
  e.onset_s = static_cast<double>(first_block * result_.block_samples) / result_.rate_hz;
  e.detected_s = static_cast<double>(blocks_done_ * result_.block_samples) / result_.rate_hz;
  e.isolated = isolable_;
  e.statistic = stat;
  e.max_statistic = stat;
  e.threshold = threshold_;
  e.alarms = 1;
  result_.faults.push_back(e);
  open_ = true;
  last_alarm_test_ = test_index;
  if (isolable_ && exclude_isolated_) exclude(best);
}

}  // namespace imunoise::redundant
