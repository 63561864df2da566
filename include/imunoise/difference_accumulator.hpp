#pragma once
// Overlapping Allan (oadev) and Hadamard (ohdev) sums over phase that arrives in pieces:
// bounded memory, and pieces accumulated separately (other threads, processes or machines)
// merge into exactly the sums of one pass.
//
// State: for each factor m, S_m = sum of squared order-th differences at lag m over every
// start k whose whole stencil [k, k + order*m] has arrived, and their count; plus the first
// and last W = order * max(m) samples. Memory is O(W + factors), independent of length.
//
// Merge algebra (A then B, B's first sample is A's last sample, as for two rate chunks
// integrated separately with the same offset): S(A+B) = S(A) + S(B) + S_cross, where the cross
// terms start in A and end in B, so they only need A's last W and B's first W samples; B's
// phase is shifted by (last of A - first of B) first. The empty accumulator is the identity.
// Push and merge give the one-pass sums to rounding (the terms are the same; only the order
// of additions and the shift differ).
#include <cstddef>
#include <span>
#include <vector>

#include "imunoise/deviation.hpp"

namespace imunoise {

class DifferenceAccumulator {
 public:
  /// estimator: Estimator::oadev or Estimator::ohdev; factors: averaging factors (>= 1).
  DifferenceAccumulator(Estimator estimator, std::vector<std::size_t> factors);

  /// Appends the next phase samples (continuing the previous ones).
  void push(std::span<const double> phase);

  /// Appends the accumulator of the samples that follow; `later`'s first sample is this
  /// one's last (its phase may start from any constant; it is shifted to continue ours).
  void merge(const DifferenceAccumulator& later);

  /// Phase samples seen (counting the shared boundary sample of a merge once).
  [[nodiscard]] std::size_t size() const { return size_; }

  /// Deviations for sample interval tau0_s (s); factors with no complete term yet get n = 0
  /// and dev = NaN.
  [[nodiscard]] std::vector<DevPoint> deviations(double tau0_s) const;

 private:
  void add_terms(std::span<const double> x, std::size_t first_end);
  void keep_edges(std::span<const double> appended);

  Estimator estimator_;
  int order_;
  std::vector<std::size_t> factors_;
  std::size_t window_ = 0;            ///< order * max factor
  std::size_t size_ = 0;
  std::vector<double> head_;          ///< first min(size, window) samples
  std::vector<double> tail_;          ///< last min(size, window) samples
  std::vector<long double> sum_sq_;
  std::vector<std::size_t> count_;
};

}  // namespace imunoise
