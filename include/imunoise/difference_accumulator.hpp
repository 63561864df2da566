#pragma once
// The Allan family (adev, oadev, mdev, tdev, hdev, ohdev) over phase that arrives in pieces:
// pieces accumulated separately (other threads, processes or machines) merge into the sums of
// one pass, in memory bounded by the largest stencil, whatever the record's length.
//
// State: for each factor m, S_m = sum of the squared terms whose whole stencil [k, k + span(m)]
// has arrived, and their count; plus the first and last W = max span(m) samples. span(m) is
// 2m (adev, oadev), 3m (hdev, ohdev) or 3m - 1 (mdev, tdev: the term at k sums the second
// differences starting at k .. k+m-1). The non-overlapping estimators (adev, hdev) take the
// terms starting at global indices 0, m, 2m, ...: an accumulator knows the global index of its
// first sample (`first_index`), so slices read at any offset keep the one-pass alignment.
//
// Merge algebra (A then B, B's first sample is A's last sample, as for two rate slices
// integrated separately with the same offset): S(A+B) = S(A) + S(B) + S_cross, where the cross
// terms start in A and end in B, so they only need A's last W and B's first W samples.
// Cancellation guard: the edges are stored relative to their own boundary sample (the tail
// minus its last sample, the head minus its first), so the cross terms are computed on small
// numbers that meet exactly (both sides are 0 at the shared sample) and never on the absolute
// level the phase has wandered to; the level only enters one scalar per edge.
// The empty accumulator is the identity. Push and merge give the one-pass sums to rounding (the
// terms are the same; only the order of the additions differs).
//
// Memory: 2 min(size, W) doubles of edges plus one long double and one count per factor;
// push(x) also holds min(size, W) + |x| doubles while it runs.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

class DifferenceAccumulator {
 public:
  /// estimator: adev, oadev, mdev, tdev, hdev or ohdev (InputError otherwise); factors:
  /// averaging factors (>= 1). first_index: global index of the first phase sample this
  /// accumulator will receive (only adev and hdev depend on it: their terms start at 0, m, 2m).
  DifferenceAccumulator(Estimator estimator, std::vector<std::size_t> factors,
                        std::size_t first_index = 0);

  /// Appends the next phase samples (continuing the previous ones, in the same coordinates).
  void push(std::span<const double> phase);

  /// Appends the accumulator of the samples that follow; `later`'s first sample is this
  /// one's last (its phase may start from any constant). For adev and hdev, later's
  /// first_index must be first_index() + size() - 1 (InputError otherwise).
  void merge(const DifferenceAccumulator& later);

  /// Phase samples seen (counting the shared boundary sample of a merge once).
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] std::size_t first_index() const { return first_index_; }
  [[nodiscard]] Estimator estimator() const { return estimator_; }
  [[nodiscard]] const std::vector<std::size_t>& factors() const { return factors_; }
  /// W: the samples kept at each edge once the accumulator holds that many.
  [[nodiscard]] std::size_t window() const { return window_; }
  /// Bytes of state (edges and sums), the memory an accumulator holds between pushes.
  [[nodiscard]] std::size_t state_bytes() const;

  /// Deviations for sample interval tau0_s (s), in the unit of the phase per second (tdev: the
  /// phase unit); factors with no complete term yet get n = 0 and dev = NaN.
  [[nodiscard]] std::vector<DevPoint> deviations(double tau0_s) const;

  /// A byte image for sending to another process of the same architecture (MPI); the inverse
  /// of from_bytes. InputError on a truncated or foreign image.
  [[nodiscard]] std::vector<std::uint8_t> to_bytes() const;
  static DifferenceAccumulator from_bytes(std::span<const std::uint8_t> bytes);

 private:
  enum class Kind { overlapping, strided, modified };

  [[nodiscard]] std::size_t span_of(std::size_t m) const;
  void first_push(std::span<const double> phase);
  void push_relative(std::span<const double> rel);
  void add_new_terms(const std::vector<double>& combined, std::size_t global0, std::size_t first_end);
  void add_range(const double* x, std::size_t global0, std::size_t t, std::size_t k_begin,
                 std::size_t k_end);
  void append_head(std::span<const double> rel, double level);

  Estimator estimator_;
  Kind kind_;
  int order_;                         ///< 2 (adev, oadev, mdev) or 3 (hdev, ohdev)
  std::vector<std::size_t> factors_;
  std::size_t first_index_ = 0;
  std::size_t window_ = 1;            ///< max span(m), at least 1
  std::size_t size_ = 0;
  double head_first_ = 0.0;           ///< first sample, in the coordinates of the pushed phase
  double tail_last_ = 0.0;            ///< last sample, same coordinates
  std::vector<double> head_rel_;      ///< first min(size, W) samples minus head_first_
  std::vector<double> tail_rel_;      ///< last min(size, W) samples minus tail_last_
  std::vector<long double> sum_sq_;
  std::vector<std::size_t> count_;
};

}  // namespace imunoise
