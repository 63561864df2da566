#include "imunoise/difference_accumulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "imunoise/error.hpp"
#include "kernels.hpp"

namespace imunoise {
namespace {

int order_of(Estimator estimator) {
  if (estimator == Estimator::oadev) return 2;
  if (estimator == Estimator::ohdev) return 3;
  throw InputError("DifferenceAccumulator supports oadev and ohdev, not " +
                   std::string(estimator_name(estimator)));
}

std::vector<double> shifted(std::span<const double> x, double shift) {
  std::vector<double> out(x.begin(), x.end());
  for (auto& v : out) v += shift;
  return out;
}

}  // namespace

DifferenceAccumulator::DifferenceAccumulator(Estimator estimator, std::vector<std::size_t> factors)
    : estimator_(estimator), order_(order_of(estimator)), factors_(std::move(factors)),
      sum_sq_(factors_.size(), 0.0L), count_(factors_.size(), 0) {
  for (const std::size_t m : factors_) {
    if (m == 0) throw InputError("averaging factors must be at least 1");
    window_ = std::max(window_, static_cast<std::size_t>(order_) * m);
  }
}

// Adds, for each factor, the terms of x (a run of consecutive samples) whose stencil ends at
// index >= first_end: the ones not complete before the samples from first_end arrived.
void DifferenceAccumulator::add_terms(std::span<const double> x, std::size_t first_end) {
  const auto kernel = order_ == 2 ? detail::sum_sq_second_difference : detail::sum_sq_third_difference;
  for (std::size_t t = 0; t < factors_.size(); ++t) {
    const std::size_t span = static_cast<std::size_t>(order_) * factors_[t];
    if (x.size() <= span) continue;
    const std::size_t k_begin = first_end > span ? first_end - span : 0;
    const std::size_t k_end = x.size() - span;  // exclusive
    if (k_end <= k_begin) continue;
    sum_sq_[t] += kernel(x.data() + k_begin, factors_[t], k_end - k_begin);
    count_[t] += k_end - k_begin;
  }
}

void DifferenceAccumulator::keep_edges(std::span<const double> appended) {
  for (std::size_t i = 0; head_.size() < window_ && i < appended.size(); ++i) {
    head_.push_back(appended[i]);
  }
}

void DifferenceAccumulator::push(std::span<const double> phase) {
  if (phase.empty()) return;
  std::vector<double> combined;
  combined.reserve(tail_.size() + phase.size());
  combined.insert(combined.end(), tail_.begin(), tail_.end());
  combined.insert(combined.end(), phase.begin(), phase.end());
  add_terms(combined, tail_.size());
  keep_edges(phase);
  const std::size_t keep = std::min(window_, combined.size());
  tail_.assign(combined.end() - static_cast<std::ptrdiff_t>(keep), combined.end());
  size_ += phase.size();
}

void DifferenceAccumulator::merge(const DifferenceAccumulator& later) {
  if (later.estimator_ != estimator_ || later.factors_ != factors_) {
    throw InputError("cannot merge accumulators of different estimators or factors");
  }
  if (later.size_ == 0) return;
  if (size_ == 0) {
    *this = later;
    return;
  }
  const double shift = tail_.back() - later.head_.front();
  const auto later_head = shifted(std::span(later.head_).subspan(1), shift);
  if (later.size_ <= later.head_.size()) {  // later is short: its head is all of it
    push(later_head);
    return;
  }
  // Cross terms: start before later's first sample (index tail_.size() - 1 of `combined`),
  // end after it. Terms that end inside later but start at or after its first sample are
  // already in later's sums, hence the cut of `combined` at the last start we may take.
  std::vector<double> combined(tail_);
  combined.insert(combined.end(), later_head.begin(), later_head.end());
  const std::size_t boundary = tail_.size() - 1;
  const auto kernel = order_ == 2 ? detail::sum_sq_second_difference : detail::sum_sq_third_difference;
  for (std::size_t t = 0; t < factors_.size(); ++t) {
    const std::size_t span = static_cast<std::size_t>(order_) * factors_[t];
    const std::size_t k_begin = boundary + 1 > span ? boundary + 1 - span : 0;
    const std::size_t k_end = std::min(boundary, combined.size() > span ? combined.size() - span : 0);
    if (k_end > k_begin) {
      sum_sq_[t] += kernel(combined.data() + k_begin, factors_[t], k_end - k_begin);
      count_[t] += k_end - k_begin;
    }
    sum_sq_[t] += later.sum_sq_[t];
    count_[t] += later.count_[t];
  }
  keep_edges(later_head);
  tail_ = shifted(later.tail_, shift);
  size_ += later.size_ - 1;
}

std::vector<DevPoint> DifferenceAccumulator::deviations(double tau0_s) const {
  const double divisor = order_ == 2 ? 2.0 : 6.0;
  std::vector<DevPoint> points(factors_.size());
  for (std::size_t t = 0; t < factors_.size(); ++t) {
    auto& p = points[t];
    p.m = factors_[t];
    p.tau_s = static_cast<double>(p.m) * tau0_s;
    p.n = count_[t];
    p.dev = p.n == 0 ? std::numeric_limits<double>::quiet_NaN()
                     : std::sqrt(static_cast<double>(sum_sq_[t]) / (divisor * static_cast<double>(p.n))) / p.tau_s;
  }
  return points;
}

}  // namespace imunoise
