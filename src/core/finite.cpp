#include "imunoise/finite.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallel.hpp"

namespace imunoise {
namespace {

// 0 when every value of the block is finite, NaN otherwise; the order of the additions does
// not change that, so the reduction may be vectorized freely.
double block_poison(const double* v, std::size_t n) {
  double s = 0.0;
#pragma omp simd reduction(+ : s)
  for (std::size_t i = 0; i < n; ++i) s += v[i] - v[i];
  return s;
}

// The first non-finite index in [begin, end), or end.
std::size_t scan(std::span<const double> values, std::size_t begin, std::size_t end) {
  constexpr std::size_t kScanBlock = 4096;
  for (std::size_t b = begin; b < end; b += kScanBlock) {
    const std::size_t n = std::min(kScanBlock, end - b);
    if (block_poison(values.data() + b, n) == 0.0) continue;
    for (std::size_t i = b; i < b + n; ++i) {
      if (!std::isfinite(values[i])) return i;
    }
  }
  return end;
}

}  // namespace

std::size_t first_non_finite(std::span<const double> values, unsigned threads) {
  // Chunks of 1 M values: one pass over memory is what this costs, so it is split over the
  // cores like the analysis; the smallest bad index over chunks is the first.
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  const std::size_t n_chunks = (values.size() + kChunk - 1) / kChunk;
  std::vector<std::size_t> first(n_chunks);
  detail::parallel_for(n_chunks, threads, [&](std::size_t c) {
    const std::size_t end = std::min(values.size(), (c + 1) * kChunk);
    first[c] = scan(values, c * kChunk, end);
  });
  for (std::size_t c = 0; c < n_chunks; ++c) {
    if (first[c] < std::min(values.size(), (c + 1) * kChunk)) return first[c];
  }
  return values.size();
}

}  // namespace imunoise
