#include "imunoise/difference_accumulator.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "imunoise/error.hpp"
#include "difference_sums.hpp"
#include "kernels.hpp"

namespace imunoise {
namespace {

// Kernel calls are cut into blocks so that each double partial sum stays short (as in the
// one-pass sums), and the blocks are added in long double.
constexpr std::size_t kBlock = 65536;

long double overlapping_sum(int order, const double* x, std::size_t m, std::size_t count) {
  const auto kernel = order == 2 ? detail::sum_sq_second_difference : detail::sum_sq_third_difference;
  long double sum = 0.0L;
  for (std::size_t k = 0; k < count; k += kBlock) {
    sum += kernel(x + k, m, std::min(kBlock, count - k));
  }
  return sum;
}

// mdev: v_k = sum_{i=k}^{k+m-1} (x[i+2m] - 2x[i+m] + x[i]), by the recursion of the one-pass
// sums (long double, restarted from a direct sum every max(kBlock, m) starts).
long double modified_sum(const double* x, std::size_t m, std::size_t count) {
  long double sum = 0.0L;
  const std::size_t block = std::max(kBlock, m);  // a restart costs O(m), as in the one-pass sums
  for (std::size_t begin = 0; begin < count; begin += block) {
    const std::size_t end = std::min(count, begin + block);
    long double v = 0.0L;
    for (std::size_t i = begin; i < begin + m; ++i) {
      v += static_cast<long double>(x[i + 2 * m]) - 2.0L * x[i + m] + x[i];
    }
    for (std::size_t k = begin; k < end; ++k) {
      sum += v * v;
      if (k + 1 < end) {
        v += (static_cast<long double>(x[k + 3 * m]) - x[k]) +
             3.0L * (static_cast<long double>(x[k + m]) - x[k + 2 * m]);
      }
    }
  }
  return sum;
}

template <typename T>
void put(std::vector<std::uint8_t>& out, const T& value) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}

template <typename T>
void put_vector(std::vector<std::uint8_t>& out, const std::vector<T>& values) {
  put(out, static_cast<std::uint64_t>(values.size()));
  const auto* p = reinterpret_cast<const std::uint8_t*>(values.data());
  out.insert(out.end(), p, p + values.size() * sizeof(T));
}

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  template <typename T>
  std::vector<T> get_vector() {
    const auto n = get<std::uint64_t>();
    if (n > bytes_.size() / sizeof(T)) fail();
    need(n * sizeof(T));
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return values;
  }
  [[nodiscard]] bool done() const { return at_ == bytes_.size(); }
  [[noreturn]] static void fail() {
    throw InputError("accumulator image is truncated or corrupt (sent by another build or "
                     "architecture?); fix: run the same imunoise executable on every rank");
  }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) fail();
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

constexpr std::uint32_t kImageMagic = 0x494d4e41;  // "IMNA", version 1

}  // namespace

DifferenceAccumulator::DifferenceAccumulator(Estimator estimator, std::vector<std::size_t> factors,
                                             std::size_t first_index)
    : estimator_(estimator), factors_(std::move(factors)), first_index_(first_index),
      window_(1), sum_sq_(factors_.size(), 0.0L), count_(factors_.size(), 0) {
  switch (estimator) {
    case Estimator::adev: kind_ = Kind::strided; order_ = 2; break;
    case Estimator::oadev: kind_ = Kind::overlapping; order_ = 2; break;
    case Estimator::mdev:
    case Estimator::tdev: kind_ = Kind::modified; order_ = 2; break;
    case Estimator::hdev: kind_ = Kind::strided; order_ = 3; break;
    case Estimator::ohdev: kind_ = Kind::overlapping; order_ = 3; break;
    default:
      throw InputError("DifferenceAccumulator supports adev, oadev, mdev, tdev, hdev and ohdev, not " +
                       std::string(estimator_name(estimator)));
  }
  for (const std::size_t m : factors_) {
    if (m == 0) throw InputError("averaging factors must be at least 1");
    window_ = std::max(window_, span_of(m));
  }
}

std::size_t DifferenceAccumulator::span_of(std::size_t m) const {
  return kind_ == Kind::modified ? 3 * m - 1 : static_cast<std::size_t>(order_) * m;
}

std::size_t DifferenceAccumulator::state_bytes() const {
  return (head_rel_.capacity() + tail_rel_.capacity()) * sizeof(double) +
         sum_sq_.size() * sizeof(long double) + count_.size() * sizeof(std::size_t) +
         factors_.size() * sizeof(std::size_t) + sizeof(*this);
}

// Adds the terms of factor t starting at k_begin <= k < k_end of the contiguous samples x,
// whose x[0] is the global sample global0.
void DifferenceAccumulator::add_range(const double* x, std::size_t global0, std::size_t t,
                                      std::size_t k_begin, std::size_t k_end) {
  if (k_end <= k_begin) return;
  const std::size_t m = factors_[t];
  switch (kind_) {
    case Kind::overlapping:
      sum_sq_[t] += overlapping_sum(order_, x + k_begin, m, k_end - k_begin);
      count_[t] += k_end - k_begin;
      return;
    case Kind::modified:
      sum_sq_[t] += modified_sum(x + k_begin, m, k_end - k_begin);
      count_[t] += k_end - k_begin;
      return;
    case Kind::strided: {
      const std::size_t phase_of_begin = (global0 + k_begin) % m;
      long double sum = 0.0L;
      std::size_t n = 0;
      for (std::size_t k = k_begin + (phase_of_begin == 0 ? 0 : m - phase_of_begin); k < k_end;
           k += m, ++n) {
        const double d = order_ == 2
                             ? x[k + 2 * m] - 2.0 * x[k + m] + x[k]
                             : x[k + 3 * m] - 3.0 * x[k + 2 * m] + 3.0 * x[k + m] - x[k];
        sum += static_cast<long double>(d) * d;
      }
      sum_sq_[t] += sum;
      count_[t] += n;
      return;
    }
  }
}

// Head samples are kept relative to the first sample; `level` is the first of `rel`'s
// reference minus head_first_.
void DifferenceAccumulator::append_head(std::span<const double> rel, double level) {
  const std::size_t take = std::min(window_ - std::min(window_, head_rel_.size()), rel.size());
  const std::size_t old = head_rel_.size();
  head_rel_.resize(old + take);
  for (std::size_t i = 0; i < take; ++i) head_rel_[old + i] = rel[i] + level;
}

// Adds, for each factor, the terms of `combined` whose stencil ends at index >= first_end (the
// ones not complete before).
void DifferenceAccumulator::add_new_terms(const std::vector<double>& combined, std::size_t global0,
                                          std::size_t first_end) {
  for (std::size_t t = 0; t < factors_.size(); ++t) {
    const std::size_t span = span_of(factors_[t]);
    if (combined.size() <= span) continue;
    // Terms not complete before: their stencil ends at index >= first_end.
    const std::size_t k_begin = first_end > span ? first_end - span : 0;
    add_range(combined.data(), global0, t, k_begin, combined.size() - span);
  }
}

// rel: the next samples minus the current last sample.
void DifferenceAccumulator::push_relative(std::span<const double> rel) {
  if (rel.empty()) return;
  std::vector<double> combined;
  combined.reserve(tail_rel_.size() + rel.size());
  combined.insert(combined.end(), tail_rel_.begin(), tail_rel_.end());
  combined.insert(combined.end(), rel.begin(), rel.end());
  const std::size_t first_end = tail_rel_.size();
  const std::size_t global0 = first_index_ + size_ - tail_rel_.size();
  add_new_terms(combined, global0, first_end);
  append_head(rel, tail_last_ - head_first_);
  const std::size_t keep = std::min(window_, combined.size());
  const double last = combined.back();
  tail_rel_.assign(combined.end() - static_cast<std::ptrdiff_t>(keep), combined.end());
  for (auto& v : tail_rel_) v -= last;
  tail_last_ += last;
  size_ += rel.size();
}

// The first push (a whole slice under --mpi, which starts at 0) needs no copy: every term is
// new, so the sums run on the samples as given, with the cache-blocked one-pass engine
// (all factors in one pass over memory) for the overlapping and modified sums; only the edges
// are copied.
void DifferenceAccumulator::first_push(std::span<const double> phase) {
  if (kind_ == Kind::strided) {
    for (std::size_t t = 0; t < factors_.size(); ++t) {
      const std::size_t span = span_of(factors_[t]);
      if (phase.size() > span) add_range(phase.data(), first_index_, t, 0, phase.size() - span);
    }
  } else {
    const auto sums = kind_ == Kind::overlapping
                          ? detail::overlapping_difference_sums(phase, order_, factors_, 1)
                          : detail::modified_difference_sums(phase, factors_, 1);
    for (std::size_t t = 0; t < factors_.size(); ++t) {
      sum_sq_[t] += sums.sum_sq[t];
      count_[t] += sums.n[t];
    }
  }
  const std::size_t keep = std::min(window_, phase.size());
  head_first_ = phase.front();
  tail_last_ = phase.back();
  head_rel_.resize(keep);
  tail_rel_.resize(keep);
  for (std::size_t i = 0; i < keep; ++i) {
    head_rel_[i] = phase[i] - head_first_;
    tail_rel_[i] = phase[phase.size() - keep + i] - tail_last_;
  }
  size_ = phase.size();
}

void DifferenceAccumulator::push(std::span<const double> phase) {
  if (phase.empty()) return;
  if (size_ == 0) {
    if (phase.front() == 0.0) {  // an integrated slice starts at 0: use it as it is
      first_push(phase);
      return;
    }
    // Otherwise relative to the first sample, so the terms never see the absolute level.
    const double level = phase.front();
    std::vector<double> rel(phase.begin(), phase.end());
    for (auto& v : rel) v -= level;
    first_push(rel);
    head_first_ += level;
    tail_last_ += level;
    return;
  }
  std::vector<double> rel(phase.begin(), phase.end());
  for (auto& v : rel) v -= tail_last_;
  push_relative(rel);
}

void DifferenceAccumulator::merge(const DifferenceAccumulator& later) {
  if (later.estimator_ != estimator_ || later.factors_ != factors_) {
    throw InputError("cannot merge accumulators of different estimators or factors");
  }
  if (later.size_ == 0) return;
  if (size_ == 0) {  // an empty accumulator has no position: the identity wherever it was
    *this = later;
    return;
  }
  if (kind_ == Kind::strided && later.first_index_ != first_index_ + size_ - 1) {
    throw InputError("cannot merge: " + std::string(estimator_name(estimator_)) +
                     " needs adjacent pieces; the later accumulator starts at sample " +
                     std::to_string(later.first_index_) + ", not at this one's last sample " +
                     std::to_string(first_index_ + size_ - 1));
  }
  const auto later_rel = std::span(later.head_rel_).subspan(1);  // relative to the shared sample
  if (later.size_ <= later.head_rel_.size()) {  // later is short: its head is all of it
    push_relative(later_rel);
    return;
  }
  // Cross terms: start before the shared sample (index boundary of `combined`), end after it.
  // Both edges are 0 at the shared sample, so the terms see no absolute level.
  std::vector<double> combined(tail_rel_);
  combined.insert(combined.end(), later_rel.begin(), later_rel.end());
  const std::size_t boundary = tail_rel_.size() - 1;
  const std::size_t global0 = first_index_ + size_ - tail_rel_.size();
  for (std::size_t t = 0; t < factors_.size(); ++t) {
    const std::size_t span = span_of(factors_[t]);
    const std::size_t k_begin = boundary + 1 > span ? boundary + 1 - span : 0;
    const std::size_t k_end = std::min(boundary, combined.size() > span ? combined.size() - span : 0);
    add_range(combined.data(), global0, t, k_begin, k_end);
    sum_sq_[t] += later.sum_sq_[t];
    count_[t] += later.count_[t];
  }
  append_head(later_rel, tail_last_ - head_first_);
  tail_rel_ = later.tail_rel_;
  tail_last_ += later.tail_last_ - later.head_first_;
  size_ += later.size_ - 1;
}

std::vector<DevPoint> DifferenceAccumulator::deviations(double tau0_s) const {
  const double divisor = order_ == 2 ? 2.0 : 6.0;
  std::vector<DevPoint> points(factors_.size());
  for (std::size_t t = 0; t < factors_.size(); ++t) {
    auto& p = points[t];
    p.m = factors_[t];
    const double m = static_cast<double>(p.m);
    p.tau_s = m * tau0_s;
    p.n = count_[t];
    if (p.n == 0) {
      p.dev = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double norm = divisor * static_cast<double>(p.n) * (kind_ == Kind::modified ? m * m : 1.0);
    p.dev = std::sqrt(static_cast<double>(sum_sq_[t]) / norm) / p.tau_s;
    if (estimator_ == Estimator::tdev) p.dev *= p.tau_s / std::sqrt(3.0);
  }
  return points;
}

std::vector<std::uint8_t> DifferenceAccumulator::to_bytes() const {
  std::vector<std::uint8_t> out;
  out.reserve(64 + (head_rel_.size() + tail_rel_.size()) * sizeof(double) +
              factors_.size() * (2 * sizeof(std::size_t) + sizeof(long double)));
  put(out, kImageMagic);
  put(out, static_cast<std::int32_t>(estimator_));
  put(out, static_cast<std::uint64_t>(first_index_));
  put(out, static_cast<std::uint64_t>(size_));
  put(out, head_first_);
  put(out, tail_last_);
  put_vector(out, factors_);
  put_vector(out, head_rel_);
  put_vector(out, tail_rel_);
  put_vector(out, sum_sq_);
  put_vector(out, count_);
  return out;
}

DifferenceAccumulator DifferenceAccumulator::from_bytes(std::span<const std::uint8_t> bytes) {
  Reader in(bytes);
  if (in.get<std::uint32_t>() != kImageMagic) Reader::fail();
  const auto estimator = static_cast<Estimator>(in.get<std::int32_t>());
  const auto first_index = in.get<std::uint64_t>();
  const auto size = in.get<std::uint64_t>();
  const double head_first = in.get<double>();
  const double tail_last = in.get<double>();
  auto factors = in.get_vector<std::size_t>();
  DifferenceAccumulator acc(estimator, std::move(factors), first_index);
  acc.size_ = size;
  acc.head_first_ = head_first;
  acc.tail_last_ = tail_last;
  acc.head_rel_ = in.get_vector<double>();
  acc.tail_rel_ = in.get_vector<double>();
  acc.sum_sq_ = in.get_vector<long double>();
  acc.count_ = in.get_vector<std::size_t>();
  const std::size_t edge = std::min<std::size_t>(size, acc.window_);
  if (!in.done() || acc.sum_sq_.size() != acc.factors_.size() ||
      acc.count_.size() != acc.factors_.size() || acc.head_rel_.size() != edge ||
      acc.tail_rel_.size() != edge) {
    Reader::fail();
  }
  return acc;
}

}  // namespace imunoise
