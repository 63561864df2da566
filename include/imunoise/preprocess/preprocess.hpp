#pragma once
// Preprocessing of real IMU records before the noise analysis, each step reporting what it
// removed: warm-up skip, polynomial detrend, spike (outlier) detection by the median absolute
// deviation, and splitting at timestamp gaps with Allan sums pooled over the segments.
//
// Nothing is interpolated or smoothed: samples are only removed (skip, rejected spikes) or a
// fitted polynomial in time is subtracted (detrend), and the record is split where samples are
// missing. All values are SI rates (rad/s, m/s^2) sampled at a fixed rate.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise::preprocess {

enum class DetrendOrder { none = 0, linear = 1, quadratic = 2 };
/// "none" | "linear" | "quadratic"; throws InputError otherwise.
DetrendOrder parse_detrend(std::string_view text);

/// The polynomial removed: value(t) = c[0] + c[1] t + c[2] t^2, t in s from the first sample.
/// Removing it also removes the rate ramp R (a linear trend of the rate IS rate ramp) and
/// biases the rate random walk K low (a random walk's own best-fit line is subtracted too).
struct DetrendReport {
  DetrendOrder order = DetrendOrder::none;
  std::vector<double> coefficients;  ///< c[0..order] in SI (unit, unit/s, unit/s^2)
  double removed_rms = 0.0;          ///< RMS of the subtracted polynomial about its mean (SI)
};

/// Subtracts the least-squares polynomial of `order` in time (sample i at t = i / rate_hz)
/// from `values` in place. The constant term is reported but also removed (every estimator
/// cancels a constant anyway).
DetrendReport detrend(std::span<double> values, double rate_hz, DetrendOrder order);

/// Spikes: samples whose robust z-score |x - median| / (1.4826 MAD) exceeds `threshold`.
struct OutlierReport {
  double median = 0.0;                ///< SI
  double robust_sigma = 0.0;          ///< 1.4826 * MAD (SI): the noise level a Gaussian would have
  double threshold_sigmas = 0.0;      ///< the z-score above which a sample is a spike
  std::vector<std::size_t> indices;   ///< 0-based samples flagged, in order
};

/// The default threshold for n samples: the z at which a Gaussian record of n samples would
/// have 0.01 false detections in expectation (two-sided), so clean records are almost never
/// flagged: 4.9 for 1e4 samples, 6.0 for 4.3e6.
double default_spike_threshold(std::size_t n);

/// Finds spikes (threshold <= 0: default_spike_threshold(values.size())). O(n) (nth_element).
/// Throws InputError when the record is constant (MAD = 0 and not all samples equal), naming
/// `source`.
OutlierReport find_spikes(std::span<const double> values, double threshold, std::string_view source);

/// A contiguous run of samples [begin, end).
struct Segment {
  std::size_t begin = 0;
  std::size_t end = 0;
  [[nodiscard]] std::size_t size() const { return end - begin; }
};

/// Splits 0..n at the given break indices (a break at i starts a new segment at sample i;
/// sample indices listed in `removed` are dropped and also break the record). Empty segments
/// are dropped.
std::vector<Segment> split_segments(std::size_t n, std::span<const std::size_t> breaks,
                                    std::span<const std::size_t> removed = {});

/// Overlapping Allan deviation of rate samples split into independent segments:
/// pooled_deviation(Estimator::oadev, ...) (pooled_deviation.hpp) at confidence `level`, the
/// points only.
std::vector<DevPoint> pooled_oadev(std::span<const double> rate_si, std::span<const Segment> segments,
                                   double tau0_s, std::span<const std::size_t> factors, double level = 0.683);

}  // namespace imunoise::preprocess
