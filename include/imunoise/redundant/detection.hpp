#pragma once
// Fault detection and isolation in the parity space of a redundant unit: a generalized
// likelihood-ratio test on a sliding window (docs/redundant.md).
//
// Every window of a = window_s seconds (one test per window), the mean of each sensor over the
// window is compared with its mean over the reference_s seconds just before:
//   d_i = mean_window(m_i) - mean_reference(m_i),   z = S^-1 d,  S = diag(sigma_i),
// sigma_i^2 the variance of d_i from sensor i's noise model (DetectionDesign). The body rate
// cancels in the whitened parity p = Vw z (Vw H_w = 0, Vw Vw^T = I, H_w = S^-1 H), so without a
// fault p ~ N(0, I_k) whatever the motion, and the GLRT of "some sensor has stepped" against
// "no fault" is T = |p|^2 ~ chi2_k. An alarm is T > chi2_k quantile at the per-test
// probability false_alarm_per_hour * window_s / 3600 (so the expected number of alarms per hour
// of clean data is the configured rate, exactly for Gaussian noise). A step b on sensor i moves
// p by (b / sigma_i) v_i (v_i column i of Vw); the GLRT isolates argmax_i (v_i . p)^2 / |v_i|^2,
// which is meaningful when the geometry is isolable (five or more sensors, no two parity
// columns parallel). The onset is the maximum-likelihood change point of the fault direction
// over the last two windows, to one block (window / blocks_per_window).
// An isolated fault excludes its sensor from the later tests (the parity of the others, one
// degree of freedom less, same per-test probability), so a second fault on another sensor can
// still be detected while the reference absorbs the first. Without isolation (four sensors),
// alarms within one reference length of each other are one fault (the reference needs that long
// to absorb a step); so are alarms on the same sensor when exclusion is off
// (DetectionOptions::exclude_isolated). Every alarm is counted in `alarms`. The detector does not reconfigure the
// fusion output (gdop_without says what the unit would give without the sensor).
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/redundant/analysis.hpp"

namespace imunoise::redundant {

struct FaultEvent {
  std::size_t sensor = 0;      ///< 0-based index of the sensor the fault is isolated to (the
                               ///< likeliest even when not isolable)
  double onset_s = 0.0;        ///< estimated onset, seconds from the first sample
  double detected_s = 0.0;     ///< end of the first window that raised the alarm (s)
  bool isolated = false;       ///< the geometry isolates single faults
  double statistic = 0.0;      ///< T of the first alarm
  double max_statistic = 0.0;  ///< largest T while the fault lasted
  double threshold = 0.0;
  std::size_t alarms = 0;      ///< alarms merged into this fault
  /// 0-based sensors whose parity columns explain the alarm equally well (to 1e-9): the sensor
  /// alone when isolated; without isolation (a tetrahedron: all four), the fault is on one of
  /// them and `sensor` is only the first among equals, set by rounding.
  std::vector<std::size_t> candidates;
};

struct DetectionResult {
  DetectionDesign design;          ///< window and reference rounded to whole samples
  double rate_hz = 0.0;
  std::size_t window_samples = 0;
  std::size_t block_samples = 0;
  std::size_t reference_windows = 0;
  std::size_t samples = 0;         ///< samples per sensor processed
  std::size_t tests = 0;
  std::size_t alarms = 0;          ///< tests above the threshold
  double max_statistic = 0.0;      ///< largest T over all tests
  std::vector<FaultEvent> faults;
  std::vector<std::size_t> excluded;  ///< isolated sensors, in the order they were excluded
};

class FaultDetector {
 public:
  /// Needs one noise model per sensor (InputError otherwise) and at least 4 sensors.
  /// The window becomes a whole number of blocks of whole samples, the reference a whole number
  /// of windows; the design reports the values used.
  FaultDetector(const Geometry& geometry, std::span<const SensorModel> sensors, double rate_hz,
                const DetectionOptions& options);

  /// The next samples of every sensor (rad/s), one span per sensor, all of the same length.
  void push(std::span<const std::span<const double>> sensors);

  [[nodiscard]] const DetectionResult& result() const { return result_; }

 private:
  void close_block();
  void update_isolable();
  void exclude(std::size_t sensor);
  void close_window();
  void test();

  std::size_t n_ = 0;
  std::size_t k_ = 0;
  bool isolable_ = false;
  std::size_t blocks_per_window_ = 0;
  std::vector<double> vw_;            // k x n whitened parity, row-major
  std::vector<double> inv_sigma_;     // 1 / sigma_i
  std::vector<double> sigma_;
  std::vector<Axis> axes_;
  std::vector<bool> active_;          // sensors still monitored
  double threshold_ = 0.0;            // for the current degrees of freedom
  bool exclude_isolated_ = true;
  std::vector<double> block_acc_;     // current block sums (n)
  std::size_t in_block_ = 0;
  std::vector<double> blocks_;        // ring of the last 2 windows' block sums (2W x n)
  std::size_t blocks_done_ = 0;
  std::vector<double> windows_;       // ring of window sums ((R + 1) x n)
  std::size_t windows_done_ = 0;
  std::size_t last_alarm_test_ = 0;
  bool open_ = false;
  DetectionResult result_;
};

}  // namespace imunoise::redundant
